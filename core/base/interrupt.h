#pragma once
// Interruption by SIGINT or SIGTERM. The first signal asks the work to stop at its next safe
// point (a render finishes its pass and writes what it has); a second one aborts at once: it
// removes the files registered with RemoveOnAbort (temporaries being written, outputs of this
// run) and exits with 128 + the signal number. Everything the handler does is
// async-signal-safe (an atomic store, unlink, _exit).

#include <atomic>
#include <filesystem>

namespace prism::interrupt {

// Installs the handlers for SIGINT and SIGTERM.
void install();
// The flag the first signal sets (a renderer polls it between passes).
const std::atomic<bool>& requested();

// Registers a file for removal if the process is aborted while this object lives.
class RemoveOnAbort {
 public:
  explicit RemoveOnAbort(const std::filesystem::path& file);
  ~RemoveOnAbort();
  RemoveOnAbort(const RemoveOnAbort&) = delete;
  RemoveOnAbort& operator=(const RemoveOnAbort&) = delete;

 private:
  int slot_ = -1;
};

}  // namespace prism::interrupt
