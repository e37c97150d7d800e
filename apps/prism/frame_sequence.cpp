#include "apps/prism/frame_sequence.h"

#include <filesystem>

#include "core/base/error.h"

namespace prism {

FrameRange parse_frames(const std::string& text) {
  FrameRange r;
  const size_t colon = text.find(':');
  try {
    size_t used_first = 0, used_last = 0;
    if (colon == std::string::npos) throw std::invalid_argument(text);
    r.first = std::stoi(text.substr(0, colon), &used_first);
    r.last = std::stoi(text.substr(colon + 1), &used_last);
    if (used_first != colon || used_last != text.size() - colon - 1) throw std::invalid_argument(text);
  } catch (const std::exception&) {
    fail("--frames '{}': expected A:B, two whole frame numbers", text);
  }
  if (r.first < 0 || r.last < r.first) fail("--frames '{}': needs 0 <= A <= B", text);
  return r;
}

std::string frame_path(const std::string& pattern, int frame) {
  const size_t end = pattern.find_last_of('#');
  if (end == std::string::npos) {
    const std::filesystem::path p(pattern);
    std::filesystem::path with = p;
    with.replace_extension();
    return frame_path(with.string() + ".####" + p.extension().string(), frame);
  }
  size_t begin = end;
  while (begin > 0 && pattern[begin - 1] == '#') --begin;
  return pattern.substr(0, begin) + fmt::format("{:0{}d}", frame, end - begin + 1) + pattern.substr(end + 1);
}

}  // namespace prism
