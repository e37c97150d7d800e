#include "core/base/log.h"

#include <atomic>
#include <cstdio>
#include <mutex>

namespace prism::log {

namespace {
std::atomic<Level> g_level{Level::info};
std::mutex g_mutex;
}  // namespace

void set_level(Level l) { g_level = l; }
Level level() { return g_level; }

void write(Level l, const std::string& message) {
  const char* prefix = l == Level::warn ? "warning: " : "";
  std::lock_guard lock(g_mutex);
  std::fprintf(stderr, "%s%s\n", prefix, message.c_str());
}

}  // namespace prism::log
