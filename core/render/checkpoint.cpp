#include "render/checkpoint.h"

#include <fstream>

#include "base/atomic_file.h"
#include "base/checksum.h"
#include "base/error.h"

namespace prism {

namespace {

// Version 3: exact fixed-point film sums (with the second replicate's), the part of the render, a
// checksum at the end.
constexpr char kMagic[8] = {'P', 'R', 'I', 'S', 'M', 'C', 'K', '3'};

// The checksum covers every byte after the magic.

struct Writer {
  std::ofstream out;
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
  template <typename T>
  void operator()(const std::vector<T>& v) {
    value(uint64_t(v.size()));
    bytes(v.data(), v.size() * sizeof(T));
  }
};

struct Reader {
  std::ifstream in;
  const std::filesystem::path& file;
  uint64_t remaining;
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
  // A film field: its stored size must be the size the film has.
  template <typename T>
  void operator()(std::vector<T>& v) {
    if (size(sizeof(T)) != v.size()) fail("{}: the checkpoint's film does not match the render", file.string());
    bytes(v.data(), v.size() * sizeof(T));
  }
};

}  // namespace

void save_checkpoint(const std::filesystem::path& file, const RenderState& state, const std::string& fingerprint) {
  write_atomically(file, [&](const std::filesystem::path& tmp) {
    Writer w{std::ofstream(tmp, std::ios::binary), {}};
    w.out.write(kMagic, sizeof(kMagic));
    w.text(fingerprint);
    const RenderPart& part = state.part;
    for (int v :
         {part.sample_begin, part.sample_end, part.total, part.crop.x0, part.crop.y0, part.crop.x1, part.crop.y1})
      w.value(int32_t(v));
    const Film& f = state.film;
    w.value(int32_t(f.width()));
    w.value(int32_t(f.height()));
    w.value(uint32_t(f.aovs()));
    w.text(f.bins().to_string());
    w.value(int32_t(state.passes));
    const RenderStats& s = state.stats;
    for (uint64_t v : {s.rays.primary, s.rays.secondary, s.rays.shadow, s.samples, s.invalid_samples}) w.value(v);
    w.value(s.seconds);
    f.visit_fields(w);
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
  if (width <= 0 || height <= 0 || uint64_t(width) * uint64_t(height) > r.remaining)
    fail("{}: the checkpoint file is truncated or damaged", file.string());
  RenderState state{Film(width, height, aovs, bins.empty() ? SpectralBins{} : SpectralBins::parse(bins))};
  state.fingerprint = fingerprint;
  state.part = part;
  state.passes = r.value<int32_t>();
  RenderStats& s = state.stats;
  for (uint64_t* v : {&s.rays.primary, &s.rays.secondary, &s.rays.shadow, &s.samples, &s.invalid_samples})
    *v = r.value<uint64_t>();
  s.seconds = r.value<double>();
  state.film.visit_fields(r);
  const uint64_t checksum = r.sum.h;
  if (r.value<uint64_t>() != checksum) fail("{}: the checkpoint file is damaged (checksum mismatch)", file.string());
  if (r.remaining != 0 || state.passes < 0) fail("{}: the checkpoint file is truncated or damaged", file.string());
  return state;
}

}  // namespace prism
