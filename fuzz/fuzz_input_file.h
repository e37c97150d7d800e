#pragma once
// The fuzzers' input written to a file, as the readers under test take paths.

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace prism::fuzz {

// A folder of this process's own, holding one file per call (overwritten).
inline std::filesystem::path input_file(const uint8_t* data, size_t size, const std::string& name) {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("prism_fuzz_" + std::to_string(getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  const auto file = dir / name;
  std::ofstream(file, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return file;
}

}  // namespace prism::fuzz
