#pragma once
// The one exception type Prism throws for bad input or missing resources. Messages name the
// file and what is wrong; apps turn it into a message on stderr and a non-zero exit code.

#include <fmt/format.h>

#include <stdexcept>
#include <string>

namespace prism {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

template <typename... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
  throw Error(fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace prism
