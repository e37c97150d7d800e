#include "core/base/data_path.h"

#include <cstdlib>

#include "core/base/error.h"

namespace prism {

std::filesystem::path data_dir() {
  if (const char* env = std::getenv("PRISM_DATA_DIR"); env && *env) return env;
  return PRISM_DATA_DIR;
}

std::filesystem::path generated_data_dir() { return PRISM_GENERATED_DATA_DIR; }

std::filesystem::path data_file(std::string_view relative) {
  for (const auto& dir : {data_dir(), generated_data_dir()})
    if (std::filesystem::exists(dir / relative)) return dir / relative;
  fail("{}: Prism data file not found (nor in {}; set PRISM_DATA_DIR to the folder holding Prism's data/)",
       (data_dir() / relative).string(), generated_data_dir().string());
}

}  // namespace prism
