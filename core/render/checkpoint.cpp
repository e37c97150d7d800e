#include "core/render/checkpoint.h"

#include <unistd.h>

#include <fstream>

#include "core/base/atomic_file.h"
#include "core/base/checksum.h"
#include "core/base/error.h"

namespace prism {

namespace {

// Version 6: exact fixed-point film sums (with the second replicate's and the XYZ products) of
// the part's window only (the crop, else the frame), then the wide sums of the window's pixels
// that have them (film.h), the part of the render, a checksum at the end.
constexpr char kMagic[8] = {'P', 'R', 'I', 'S', 'M', 'C', 'K', '6'};

// The wide sums of one pixel, field by field, in a fixed order.
template <typename Sums, typename Visit>
void visit_wide_sums(Sums& w, Visit&& visit) {
  for (auto* field : {&w.sum, &w.sq, &w.cross, &w.second_sum, &w.splat})
    for (auto& sum : *field) visit(sum);
  for (auto& sum : w.spectral) visit(sum);
}

// The checksum covers every byte after the magic.

// The pixels a state's film fields are stored for: the crop window, or the whole frame.
PixelWindow stored_window(const RenderPart& part, int width, int height) {
  return part.crop.empty() ? PixelWindow{0, 0, width, height} : part.crop;
}

// Calls visit(offset, count) for each row of `w` in a film field of `per_pixel` values per pixel
// of a frame `width` pixels wide: the row's first value and its value count.
template <typename Visit>
void for_rows(const PixelWindow& w, int width, size_t per_pixel, Visit&& visit) {
  for (int y = w.y0; y < w.y1; ++y) visit((size_t(y) * width + w.x0) * per_pixel, size_t(w.x1 - w.x0) * per_pixel);
}

struct Writer {
  std::ofstream out;
  PixelWindow window;
  int width;
  size_t pixels;
  Checksum sum;
  void bytes(const void* p, uint64_t n) {
    out.write(static_cast<const char*>(p), std::streamsize(n));
    sum.add(p, n);
  }
  template <typename T>
  void value(const T& v) {
    bytes(&v, sizeof(T));
  }
  void text(const std::string& s) {
    value(uint64_t(s.size()));
    bytes(s.data(), s.size());
  }
  // A film field, the window's pixels only.
  template <typename T>
  void operator()(const std::vector<T>& v) {
    const size_t per_pixel = v.size() / pixels;
    value(uint64_t(size_t(window.x1 - window.x0) * size_t(window.y1 - window.y0) * per_pixel));
    for_rows(window, width, per_pixel, [&](size_t at, size_t n) { bytes(v.data() + at, n * sizeof(T)); });
  }
};

struct Reader {
  std::ifstream in;
  const std::filesystem::path& file;
  uint64_t remaining;
  PixelWindow window{};
  int width = 0;
  size_t pixels = 1;
  Checksum sum{};
  void bytes(void* p, uint64_t n) {
    if (n > remaining || !in.read(static_cast<char*>(p), std::streamsize(n)))
      fail("{}: the checkpoint file is truncated or damaged", file.string());
    remaining -= n;
    sum.add(p, n);
  }
  template <typename T>
  T value() {
    T v;
    bytes(&v, sizeof(T));
    return v;
  }
  std::string text() {
    std::string s(size_t(size(1)), '\0');
    bytes(s.data(), s.size());
    return s;
  }
  uint64_t size(size_t element) {
    const uint64_t n = value<uint64_t>();
    if (n > remaining / element) fail("{}: the checkpoint file is truncated or damaged", file.string());
    return n;
  }
  // A film field, the window's pixels only (the film is zero elsewhere): its stored size must be
  // the window's in the film's layout.
  template <typename T>
  void operator()(std::vector<T>& v) {
    const size_t per_pixel = v.size() / pixels;
    if (size(sizeof(T)) != size_t(window.x1 - window.x0) * size_t(window.y1 - window.y0) * per_pixel)
      fail("{}: the checkpoint's film does not match the render", file.string());
    for_rows(window, width, per_pixel, [&](size_t at, size_t n) { bytes(v.data() + at, n * sizeof(T)); });
  }
};

}  // namespace

void save_checkpoint(const std::filesystem::path& file, const RenderState& state, const std::string& fingerprint) {
  write_atomically(file, [&](const std::filesystem::path& tmp) {
    const Film& f = state.film;
    Writer w{std::ofstream(tmp, std::ios::binary),
             stored_window(state.part, f.width(), f.height()),
             f.width(),
             f.pixel_count(),
             {}};
    w.out.write(kMagic, sizeof(kMagic));
    w.text(fingerprint);
    const RenderPart& part = state.part;
    for (int v :
         {part.sample_begin, part.sample_end, part.total, part.crop.x0, part.crop.y0, part.crop.x1, part.crop.y1})
      w.value(int32_t(v));
    w.value(int32_t(f.width()));
    w.value(int32_t(f.height()));
    w.value(uint32_t(f.aovs()));
    w.text(f.bins().to_string());
    w.value(int32_t(state.passes));
    const RenderStats& s = state.stats;
    for (uint64_t v : {s.rays.primary, s.rays.secondary, s.rays.shadow, s.samples, s.invalid_samples}) w.value(v);
    w.value(s.seconds);
    f.visit_fields(w);
    uint64_t wide_pixels = 0;
    const PixelWindow& window = w.window;
    const auto in_window = [&](size_t p) { return window.contains(int(p % f.width()), int(p / f.width())); };
    f.visit_wide([&](size_t p, const Film::WideSums&) { wide_pixels += in_window(p); });
    w.value(wide_pixels);
    f.visit_wide([&](size_t p, const Film::WideSums& sums) {
      if (!in_window(p)) return;
      w.value(uint64_t(p));
      visit_wide_sums(sums, [&](const WideSum& sum) { w.bytes(sum.words().data(), sizeof(sum.words())); });
    });
    const uint64_t checksum = w.sum.h;
    w.value(checksum);
    w.out.close();
    if (!w.out) throw std::runtime_error("write error");
  });
}

RenderState load_checkpoint(const std::filesystem::path& file, const std::string& fingerprint) {
  RenderState state = load_render_state(file);
  if (state.fingerprint != fingerprint)
    fail("{}: the checkpoint was written for another scene or other options; render without --resume", file.string());
  return state;
}

RenderState load_render_state(const std::filesystem::path& file) {
  std::error_code ec;
  const uint64_t length = std::filesystem::file_size(file, ec);
  if (ec) fail("{}: cannot read the checkpoint: {}", file.string(), ec.message());
  Reader r{std::ifstream(file, std::ios::binary), file, length};
  char magic[sizeof(kMagic)];
  r.bytes(magic, sizeof(magic));
  if (!std::equal(magic, magic + sizeof(magic), kMagic))
    fail("{}: not a Prism checkpoint or part file (of this version)", file.string());
  r.sum = {};  // the checksum covers what follows the magic
  const std::string fingerprint = r.text();
  RenderPart part;
  for (int* v :
       {&part.sample_begin, &part.sample_end, &part.total, &part.crop.x0, &part.crop.y0, &part.crop.x1, &part.crop.y1})
    *v = r.value<int32_t>();
  const int width = r.value<int32_t>(), height = r.value<int32_t>();
  const uint32_t aovs = r.value<uint32_t>();
  const std::string bins = r.text();
  if (width <= 0 || height <= 0) fail("{}: the checkpoint file is truncated or damaged", file.string());
  if (!(part.sample_begin >= 0 && part.sample_begin <= part.sample_end && part.sample_end <= part.total))
    fail("{}: the checkpoint's sample range {}:{} of {} is not a range of the render (damaged?)", file.string(),
         part.sample_begin, part.sample_end, part.total);
  // The window's sums are stored; the film in memory is the frame's. Both are checked before the
  // film is allocated: the window against the file's length, the frame against the machine.
  const SpectralBins spectral_bins = bins.empty() ? SpectralBins{} : SpectralBins::parse(bins);
  const uint64_t bytes_per_pixel = Film::bytes_per_pixel(aovs, spectral_bins),
                 stored_per_pixel = Film::field_bytes_per_pixel(aovs, spectral_bins);
  const PixelWindow window = stored_window(part, width, height);
  const PixelWindow& c = part.crop;
  if (!c.empty() && (c.x0 < 0 || c.y0 < 0 || c.x1 > width || c.y1 > height))
    fail("{}: the checkpoint's crop window lies outside its {}x{} frame (damaged?)", file.string(), width, height);
  if (uint64_t(window.x1 - window.x0) * uint64_t(window.y1 - window.y0) > r.remaining / stored_per_pixel)
    fail("{}: the checkpoint file is truncated or damaged", file.string());
  const uint64_t memory = uint64_t(sysconf(_SC_PHYS_PAGES)) * uint64_t(sysconf(_SC_PAGE_SIZE));
  if (uint64_t(width) * uint64_t(height) > memory / bytes_per_pixel)
    fail("{}: the checkpoint's {}x{} frame needs more memory than this machine has (damaged?)", file.string(), width,
         height);
  RenderState state{Film(width, height, aovs, spectral_bins)};
  r.window = window;
  r.width = width;
  r.pixels = state.film.pixel_count();
  state.fingerprint = fingerprint;
  state.part = part;
  state.passes = r.value<int32_t>();
  RenderStats& s = state.stats;
  for (uint64_t* v : {&s.rays.primary, &s.rays.secondary, &s.rays.shadow, &s.samples, &s.invalid_samples})
    *v = r.value<uint64_t>();
  s.seconds = r.value<double>();
  state.film.visit_fields(r);
  const uint64_t wide_pixels = r.value<uint64_t>();
  for (uint64_t i = 0; i < wide_pixels; ++i) {
    const uint64_t p = r.value<uint64_t>();
    if (p >= state.film.pixel_count() || !window.contains(int(p % width), int(p / width)))
      fail("{}: the checkpoint file is truncated or damaged", file.string());
    visit_wide_sums(state.film.wide(p), [&](WideSum& sum) { r.bytes(sum.words().data(), sizeof(sum.words())); });
  }
  const uint64_t checksum = r.sum.h;
  if (r.value<uint64_t>() != checksum) fail("{}: the checkpoint file is damaged (checksum mismatch)", file.string());
  if (r.remaining != 0 || state.passes < 0) fail("{}: the checkpoint file is truncated or damaged", file.string());
  return state;
}

}  // namespace prism
