#pragma once
// Log messages to stderr. Levels: quiet < warn < info < verbose.

#include <fmt/format.h>

#include <string>

namespace prism::log {

enum class Level { quiet, warn, info, verbose };
void set_level(Level level);
Level level();

void write(Level level, const std::string& message);

template <typename... Args>
void info(fmt::format_string<Args...> f, Args&&... args) {
  if (level() >= Level::info) write(Level::info, fmt::format(f, std::forward<Args>(args)...));
}
template <typename... Args>
void warn(fmt::format_string<Args...> f, Args&&... args) {
  if (level() >= Level::warn) write(Level::warn, fmt::format(f, std::forward<Args>(args)...));
}
template <typename... Args>
void verbose(fmt::format_string<Args...> f, Args&&... args) {
  if (level() >= Level::verbose) write(Level::verbose, fmt::format(f, std::forward<Args>(args)...));
}

}  // namespace prism::log
