#pragma once
// The fuzzers' input written to a file, as the readers under test take paths.

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

namespace prism::fuzz {

// A folder of this process's own, removed when the fuzzer exits.
struct ScratchFolder {
  std::filesystem::path path = std::filesystem::temp_directory_path() / ("prism_fuzz_" + std::to_string(getpid()));
  ScratchFolder() { std::filesystem::create_directories(path); }
  ~ScratchFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

// The input as a file in that folder, one file per name (overwritten at each call).
inline std::filesystem::path input_file(const uint8_t* data, size_t size, const std::string& name) {
  static const ScratchFolder folder;
  const auto file = folder.path / name;
  std::ofstream(file, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return file;
}

}  // namespace prism::fuzz
