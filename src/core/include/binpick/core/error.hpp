#pragma once
// Error type for bad input and bad configuration. Expected outcomes (nothing found, empty bin)
// are values, never exceptions; this is thrown only when a file, field or argument is wrong, and
// its message names what was wrong.
#include <sstream>
#include <stdexcept>
#include <string>

namespace binpick::core {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// The check of every params struct's validate(): throws "OWNER.FIELD must be RULE (got VALUE)"
// unless `ok`.
template <typename T>
void requireField(bool ok, const std::string& owner, const char* field, const char* rule, const T& value) {
  if (ok) return;
  std::ostringstream message;
  message << owner << "." << field << " must be " << rule << " (got " << value << ")";
  throw Error(message.str());
}

}  // namespace binpick::core
