#pragma once
// Error type for bad input and bad configuration. Expected outcomes (nothing found, empty bin)
// are values, never exceptions; this is thrown only when a file, field or argument is wrong, and
// its message names what was wrong.
#include <stdexcept>
#include <string>

namespace binpick {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace binpick
