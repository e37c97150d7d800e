#pragma once
// Checkpoint files, which are also the part files of a split render (merge.h): a render's state
// (the film's exact sums and sample counts, the part of the render, the passes done, the
// statistics, a checksum) with a fingerprint of everything that shapes the image, so
// that `--resume` continues a render only with the same scene and options and its result equals
// the uninterrupted render bit for bit. Written atomically (atomic_file.h).

#include <filesystem>
#include <string>

#include "core/render/renderer.h"

namespace prism {

void save_checkpoint(const std::filesystem::path& file, const RenderState& state, const std::string& fingerprint);

// Loads the state saved in `file`; fails naming the file if it is not a checkpoint, is damaged,
// or was written for another fingerprint.
RenderState load_checkpoint(const std::filesystem::path& file, const std::string& fingerprint);

// Loads the state saved in `file` whatever its fingerprint (kept in RenderState::fingerprint).
RenderState load_render_state(const std::filesystem::path& file);

}  // namespace prism
