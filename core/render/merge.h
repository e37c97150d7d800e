#pragma once
// Joins the parts of a split render (sample ranges [A, B) of a TOTAL-spp render, crop windows,
// or both; each part a render state as checkpoint.h saves it) into the state of the whole
// render. The film's sums are exact (fixed_point.h), so the merged film equals the film of the
// single-process render with the same seed and TOTAL bit for bit, whatever the split.

#include <filesystem>
#include <vector>

#include "core/render/renderer.h"

namespace prism {

// Loads the part files one at a time (memory: the merged film and one part) and merges them;
// fails, naming the files and what is wrong, unless the parts were rendered with the same
// fingerprint (scene, options, seed; animation time: parts of different frames never merge), size
// and TOTAL, and their (crop, range) pairs cover every pixel's samples [0, TOTAL) exactly once.
RenderState merge_parts(const std::vector<std::filesystem::path>& files);

}  // namespace prism
