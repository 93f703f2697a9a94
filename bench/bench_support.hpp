#pragma once
// Small helpers shared by the benchmark executables.
#include <sstream>
#include <string>
#include <vector>

namespace binpick::bench {

// "a,b,,c" -> {"a", "b", "c"}: the value of a list option such as --parts.
inline std::vector<std::string> splitCommas(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

}  // namespace binpick::bench
