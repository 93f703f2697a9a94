#include "arguments.hpp"

#include <cmath>

#include "binpick/core/error.hpp"

namespace binpick::cli {

Arguments::Arguments(const std::vector<std::string>& args, const std::set<std::string>& valued,
                     const std::set<std::string>& flags) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& name = args[i];
    if (flags.count(name)) {
      flags_.insert(name);
    } else if (valued.count(name)) {
      if (i + 1 >= args.size()) throw core::Error(name + " needs a value");
      if (!values_.emplace(name, args[++i]).second) throw core::Error(name + " is given twice");
    } else {
      throw core::Error("unknown option '" + name + "'");
    }
  }
}

std::optional<std::string> Arguments::value(const std::string& name) const {
  const auto it = values_.find(name);
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

std::string Arguments::required(const std::string& name) const {
  const auto v = value(name);
  if (!v) throw core::Error(name + " is required");
  return *v;
}

namespace {

// Parses the whole text with `parse` (std::stoi, std::stod, ...) or throws naming the option.
template <class T, class Parse>
T parseWhole(const std::string& name, const std::string& text, const char* kind, Parse parse) {
  std::size_t used = 0;
  T parsed{};
  try {
    parsed = parse(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(static_cast<double>(parsed))) {
    throw core::Error(name + " needs " + kind + ", not '" + text + "'");
  }
  return parsed;
}

}  // namespace

int parseInteger(const std::string& name, const std::string& text) {
  return parseWhole<int>(name, text, "a whole number",
                         [](const std::string& t, std::size_t* used) { return std::stoi(t, used); });
}

std::optional<int> Arguments::integer(const std::string& name) const {
  const auto v = value(name);
  if (!v) return std::nullopt;
  return parseInteger(name, *v);
}

std::optional<double> Arguments::number(const std::string& name) const {
  const auto v = value(name);
  if (!v) return std::nullopt;
  return parseWhole<double>(name, *v, "a number",
                            [](const std::string& t, std::size_t* used) { return std::stod(t, used); });
}

}  // namespace binpick::cli
