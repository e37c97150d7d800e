#include "core/base/atomic_file.h"

#include <unistd.h>

#include "core/base/error.h"
#include "core/base/interrupt.h"

namespace prism {

void write_atomically(const std::filesystem::path& file,
                      const std::function<void(const std::filesystem::path&)>& write) {
  const auto dir = file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!std::filesystem::is_directory(dir)) fail("{}: cannot create the folder {}", file.string(), dir.string());
  const auto temporary = dir / fmt::format(".{}.tmp{}", file.filename().string(), getpid());
  const interrupt::RemoveOnAbort remove_on_abort(temporary);
  try {
    write(temporary);
    std::filesystem::rename(temporary, file);
  } catch (const std::exception& e) {
    std::filesystem::remove(temporary, ec);
    fail("{}: cannot write: {}", file.string(), e.what());
  }
}

}  // namespace prism
