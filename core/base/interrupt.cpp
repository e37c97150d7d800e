#include "core/base/interrupt.h"

#include <signal.h>
#include <unistd.h>

#include <cstring>

namespace prism::interrupt {

namespace {

constexpr int kSlots = 8;
constexpr size_t kPathMax = 4096;

std::atomic<bool> g_requested{false};
std::atomic<int> g_signals{0};
// Registered paths: a claimed slot's path is written before it is marked used, and the handler
// reads only used slots.
char g_paths[kSlots][kPathMax];
std::atomic<bool> g_claimed[kSlots], g_used[kSlots];

void handle(int sig) {
  if (g_signals.fetch_add(1) == 0) {
    g_requested.store(true);
    static const char message[] = "\nprism: stopping after this pass (signal again to abort at once)\n";
    [[maybe_unused]] const ssize_t n = write(STDERR_FILENO, message, sizeof(message) - 1);
    return;
  }
  for (int i = 0; i < kSlots; ++i)
    if (g_used[i].load()) unlink(g_paths[i]);
  _exit(128 + sig);
}

}  // namespace

void install() {
  struct sigaction action {};
  action.sa_handler = handle;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

const std::atomic<bool>& requested() { return g_requested; }

RemoveOnAbort::RemoveOnAbort(const std::filesystem::path& file) {
  const std::string s = file.string();
  if (s.size() >= kPathMax) return;
  for (int i = 0; i < kSlots; ++i) {
    if (g_claimed[i].exchange(true)) continue;
    std::memcpy(g_paths[i], s.c_str(), s.size() + 1);
    g_used[i].store(true);
    slot_ = i;
    return;
  }
}

RemoveOnAbort::~RemoveOnAbort() {
  if (slot_ < 0) return;
  g_used[slot_].store(false);
  g_claimed[slot_].store(false);
}

}  // namespace prism::interrupt
