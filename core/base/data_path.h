#pragma once
// Locates Prism's run-time data (CIE tables, spectral tables, OCIO config, default scenes).

#include <filesystem>
#include <string_view>

namespace prism {

// The data directory: $PRISM_DATA_DIR if set, else the source tree's data/ folder.
std::filesystem::path data_dir();

// Where the build puts data it generates (the RGB-to-spectrum table): build/data.
std::filesystem::path generated_data_dir();

// A file below data_dir(), or else below generated_data_dir(); throws prism::Error naming the
// path when neither holds it.
std::filesystem::path data_file(std::string_view relative);

}  // namespace prism
