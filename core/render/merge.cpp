#include "render/merge.h"

#include <algorithm>
#include <map>
#include <sstream>

#include "base/error.h"

namespace prism {

namespace {

// The first `key=value` of the fingerprint a that differs in b, for the error message.
std::string first_difference(const std::string& a, const std::string& b) {
  std::istringstream sa(a), sb(b);
  std::string ta, tb;
  while (sa >> ta) {
    if (!(sb >> tb) || ta != tb) return fmt::format("{} vs {}", ta, tb);
  }
  return "the options";
}

// The value of `key=value` in a fingerprint, or "" without it.
std::string fingerprint_value(const std::string& fingerprint, const std::string& key) {
  std::istringstream s(fingerprint);
  std::string token;
  while (s >> token)
    if (token.starts_with(key + "=")) return token.substr(key.size() + 1);
  return "";
}

// A fingerprint's time= value in words.
std::string animation_time(const std::string& value) { return value == "-" ? "the file's own pose" : value + " s"; }

PixelWindow frame_window(const RenderPart& part, const Film& film) {
  return part.crop.empty() ? PixelWindow{0, 0, film.width(), film.height()} : part.crop;
}

std::string to_string(const PixelWindow& w) { return fmt::format("{},{},{},{}", w.x0, w.y0, w.x1, w.y1); }

}  // namespace

RenderState merge_parts(const std::vector<NamedState>& parts) {
  if (parts.empty()) fail("merge: no part files given");
  const NamedState& first = parts.front();
  const Film& film0 = first.state.film;
  const int total = first.state.part.total;
  const std::string time = fingerprint_value(first.state.fingerprint, "time");
  for (const NamedState& p : parts) {
    if (const std::string t = fingerprint_value(p.state.fingerprint, "time"); t != time)
      fail(
          "{}: a part of the frame at {}, {} of the frame at {}: parts of different frames never merge into one "
          "image; merge each frame's parts on their own",
          p.file.string(), animation_time(t), first.file.string(), animation_time(time));
    if (p.state.fingerprint != first.state.fingerprint)
      fail("{}: rendered with another scene or other options than {} ({})", p.file.string(), first.file.string(),
           first_difference(p.state.fingerprint, first.state.fingerprint));
    if (!p.state.film.same_layout(film0))
      fail("{}: its film ({}x{}, AOVs, spectral bins) differs from that of {}", p.file.string(), p.state.film.width(),
           p.state.film.height(), first.file.string());
    if (p.state.part.total != total)
      fail("{}: a part of a {}-spp render, {} is of a {}-spp render", p.file.string(), p.state.part.total,
           first.file.string(), total);
  }
  // Parts grouped by window: each window's ranges must tile [0, TOTAL).
  std::map<std::tuple<int, int, int, int>, std::vector<const NamedState*>> windows;
  for (const NamedState& p : parts) {
    const PixelWindow w = frame_window(p.state.part, film0);
    windows[{w.x0, w.y0, w.x1, w.y1}].push_back(&p);
  }
  int64_t area = 0;
  std::vector<PixelWindow> seen;
  for (auto& [key, group] : windows) {
    const PixelWindow w{std::get<0>(key), std::get<1>(key), std::get<2>(key), std::get<3>(key)};
    for (const PixelWindow& o : seen)
      if (std::max(w.x0, o.x0) < std::min(w.x1, o.x1) && std::max(w.y0, o.y0) < std::min(w.y1, o.y1))
        fail("merge: the crop windows {} and {} overlap", to_string(w), to_string(o));
    seen.push_back(w);
    area += int64_t(w.x1 - w.x0) * (w.y1 - w.y0);
    std::sort(group.begin(), group.end(),
              [](auto* a, auto* b) { return a->state.part.sample_begin < b->state.part.sample_begin; });
    int next = 0;
    for (const NamedState* p : group) {
      const RenderPart& r = p->state.part;
      if (r.sample_begin > next)
        fail("merge: samples {}:{} of window {} are missing (no part renders them)", next, r.sample_begin,
             to_string(w));
      if (r.sample_begin < next)
        fail("{}: its samples {}:{} overlap those of another part in window {}", p->file.string(), r.sample_begin,
             r.sample_end, to_string(w));
      const Film& f = p->state.film;
      for (int y = 0; y < f.height(); ++y)
        for (int x = 0; x < f.width(); ++x)
          if (f.samples(size_t(y) * f.width() + x) != (w.contains(x, y) ? uint32_t(r.sample_end - r.sample_begin) : 0))
            fail("{}: pixel ({}, {}) has {} samples, not those of samples {}:{} in window {} (an unfinished part?)",
                 p->file.string(), x, y, f.samples(size_t(y) * f.width() + x), r.sample_begin, r.sample_end,
                 to_string(w));
      next = r.sample_end;
    }
    if (next != total)
      fail("merge: samples {}:{} of window {} are missing (no part renders them)", next, total, to_string(w));
  }
  if (area != int64_t(film0.width()) * film0.height())
    fail("merge: the crop windows cover {} of the frame's {}x{} pixels; tiles are missing", area, film0.width(),
         film0.height());
  RenderState merged{Film(film0.width(), film0.height(), film0.aovs(), film0.bins())};
  merged.fingerprint = first.state.fingerprint;
  merged.part = {0, total, total, {}};
  for (const NamedState& p : parts) {
    merged.film.merge(p.state.film);
    merged.passes = std::max(merged.passes, p.state.passes);
    RenderStats& s = merged.stats;
    s.rays += p.state.stats.rays;
    s.samples += p.state.stats.samples;
    s.invalid_samples += p.state.stats.invalid_samples;
    s.seconds += p.state.stats.seconds;
  }
  return merged;
}

}  // namespace prism
