#include "core/base/progress.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

namespace prism {

namespace {
std::string format_seconds(double s) {
  if (s < 60) return fmt::format("{:.0f}s", s);
  if (s < 3600) return fmt::format("{}m{:02}s", int(s) / 60, int(s) % 60);
  return fmt::format("{}h{:02}m", int(s) / 3600, (int(s) / 60) % 60);
}
}  // namespace

Progress::Progress(std::string title, int64_t total, bool enabled)
    : title_(std::move(title)),
      total_(total > 0 ? total : 1),
      enabled_(enabled),
      tty_(isatty(STDERR_FILENO)),
      start_(std::chrono::steady_clock::now()),
      last_print_(start_) {}

Progress::~Progress() { finish(); }

void Progress::advance(int64_t n) {
  const int64_t done = done_.fetch_add(n) + n;
  if (!enabled_) return;
  std::unique_lock lock(mutex_, std::try_to_lock);
  if (lock.owns_lock()) print(done, false);
}

void Progress::finish() {
  std::lock_guard lock(mutex_);
  if (finished_ || !enabled_) return;
  finished_ = true;
  print(done_.load(), true);
}

void Progress::print(int64_t done, bool final) {
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double fraction = std::min(1.0, double(done) / double(total_));
  if (tty_) {
    if (!final && now - last_print_ < std::chrono::milliseconds(100)) return;
    last_print_ = now;
    constexpr int kWidth = 30;
    const int filled = int(fraction * kWidth);
    const std::string bar = std::string(filled, '#') + std::string(kWidth - filled, '.');
    const std::string eta = fraction > 0 && !final ? " ETA " + format_seconds(elapsed * (1 - fraction) / fraction) : "";
    std::fprintf(stderr, "\r%s [%s] %3.0f%% %s%s   %s", title_.c_str(), bar.c_str(), 100 * fraction,
                 format_seconds(elapsed).c_str(), eta.c_str(), final ? "\n" : "");
    std::fflush(stderr);
  } else {
    const int decile = int(fraction * 10);
    if (decile <= last_decile_ && !final) return;
    if (final && decile <= last_decile_) return;
    last_decile_ = decile;
    std::fprintf(stderr, "%s: %3d%% after %s\n", title_.c_str(), decile * 10, format_seconds(elapsed).c_str());
  }
}

}  // namespace prism
