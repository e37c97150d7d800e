#pragma once
// Writing a file atomically: to a temporary file in the destination folder, renamed into place
// only when complete, so a failed or interrupted write never leaves a half-written file (and an
// aborted process removes the temporary: interrupt.h).

#include <filesystem>
#include <functional>

namespace prism {

// Calls write(temporary_path), then renames the temporary over `file`; fails with a message
// naming `file` when either step throws.
void write_atomically(const std::filesystem::path& file,
                      const std::function<void(const std::filesystem::path&)>& write);

}  // namespace prism
