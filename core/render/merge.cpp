#include "core/render/merge.h"

#include <algorithm>
#include <map>
#include <optional>
#include <sstream>

#include "core/base/error.h"
#include "core/render/checkpoint.h"

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

RenderState merge_parts(const std::vector<std::filesystem::path>& files) {
  if (files.empty()) fail("merge: no part files given");
  // Each part is loaded, checked against the first and added in turn: memory holds the merged
  // film and one part, whatever their number. Only the parts' windows and ranges are kept.
  struct Seen {
    std::filesystem::path file;
    PixelWindow window;
    int begin, end;
  };
  std::vector<Seen> parts;
  std::optional<RenderState> merged;
  std::string time;
  for (const std::filesystem::path& file : files) {
    const RenderState p = load_render_state(file);
    const std::filesystem::path& first = parts.empty() ? file : parts.front().file;
    if (!merged) {
      merged.emplace(RenderState{Film(p.film.width(), p.film.height(), p.film.aovs(), p.film.bins())});
      merged->fingerprint = p.fingerprint;
      merged->part = {0, p.part.total, p.part.total, {}};
      time = fingerprint_value(p.fingerprint, "time");
    }
    if (const std::string t = fingerprint_value(p.fingerprint, "time"); t != time)
      fail(
          "{}: a part of the frame at {}, {} of the frame at {}: parts of different frames never merge into one "
          "image; merge each frame's parts on their own",
          file.string(), animation_time(t), first.string(), animation_time(time));
    if (p.fingerprint != merged->fingerprint)
      fail("{}: rendered with another scene or other options than {} ({})", file.string(), first.string(),
           first_difference(p.fingerprint, merged->fingerprint));
    if (!p.film.same_layout(merged->film))
      fail("{}: its film ({}x{}, AOVs, spectral bins) differs from that of {}", file.string(), p.film.width(),
           p.film.height(), first.string());
    if (p.part.total != merged->part.total)
      fail("{}: a part of a {}-spp render, {} is of a {}-spp render", file.string(), p.part.total, first.string(),
           merged->part.total);
    const PixelWindow w = frame_window(p.part, p.film);
    const RenderPart& r = p.part;
    for (int y = 0; y < p.film.height(); ++y)
      for (int x = 0; x < p.film.width(); ++x)
        if (const uint32_t n = p.film.samples(size_t(y) * p.film.width() + x);
            n != (w.contains(x, y) ? uint32_t(r.sample_end - r.sample_begin) : 0))
          fail("{}: pixel ({}, {}) has {} samples, not those of samples {}:{} in window {} (an unfinished part?)",
               file.string(), x, y, n, r.sample_begin, r.sample_end, to_string(w));
    parts.push_back({file, w, r.sample_begin, r.sample_end});
    merged->film.merge(p.film);
    merged->passes = std::max(merged->passes, p.passes);
    RenderStats& s = merged->stats;
    s.rays += p.stats.rays;
    s.samples += p.stats.samples;
    s.invalid_samples += p.stats.invalid_samples;
    s.seconds += p.stats.seconds;
  }
  // Parts grouped by window: each window's ranges must tile [0, TOTAL), the windows the frame.
  std::map<std::tuple<int, int, int, int>, std::vector<const Seen*>> windows;
  for (const Seen& p : parts) windows[{p.window.x0, p.window.y0, p.window.x1, p.window.y1}].push_back(&p);
  int64_t area = 0;
  std::vector<PixelWindow> seen;
  for (auto& [key, group] : windows) {
    const PixelWindow w = group.front()->window;
    for (const PixelWindow& o : seen)
      if (std::max(w.x0, o.x0) < std::min(w.x1, o.x1) && std::max(w.y0, o.y0) < std::min(w.y1, o.y1))
        fail("merge: the crop windows {} and {} overlap", to_string(w), to_string(o));
    seen.push_back(w);
    area += int64_t(w.x1 - w.x0) * (w.y1 - w.y0);
    std::sort(group.begin(), group.end(), [](const Seen* a, const Seen* b) { return a->begin < b->begin; });
    int next = 0;
    for (const Seen* p : group) {
      if (p->begin > next)
        fail("merge: samples {}:{} of window {} are missing (no part renders them)", next, p->begin, to_string(w));
      if (p->begin < next)
        fail("{}: its samples {}:{} overlap those of another part in window {}", p->file.string(), p->begin, p->end,
             to_string(w));
      next = p->end;
    }
    if (next != merged->part.total)
      fail("merge: samples {}:{} of window {} are missing (no part renders them)", next, merged->part.total,
           to_string(w));
  }
  const Film& film = merged->film;
  if (area != int64_t(film.width()) * film.height())
    fail("merge: the crop windows cover {} of the frame's {}x{} pixels; tiles are missing", area, film.width(),
         film.height());
  return std::move(*merged);
}

}  // namespace prism
