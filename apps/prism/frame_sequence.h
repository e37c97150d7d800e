#pragma once
// `--frames A:B`: the frame range of an animation render, and each frame's file name.

#include <string>

namespace prism {

struct FrameRange {
  int first = 0, last = 0;  // inclusive
};

// "A:B" with 0 ≤ A ≤ B; fails with a clear message otherwise.
FrameRange parse_frames(const std::string& text);

// `pattern` with its last run of '#' replaced by the frame number padded with zeros to the run's
// length (out.####.exr, frame 7: out.0007.exr); without a '#', ".####" goes before the extension.
std::string frame_path(const std::string& pattern, int frame);

}  // namespace prism
