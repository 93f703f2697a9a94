#include "arguments.hpp"

#include <cmath>

#include "binpick/io/error.hpp"

namespace binpick::cli {

Arguments::Arguments(const std::vector<std::string>& args, const std::set<std::string>& valued,
                     const std::set<std::string>& flags) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& name = args[i];
    if (flags.count(name)) {
      flags_.insert(name);
    } else if (valued.count(name)) {
      if (i + 1 >= args.size()) throw Error(name + " needs a value");
      if (!values_.emplace(name, args[++i]).second) throw Error(name + " is given twice");
    } else {
      throw Error("unknown option '" + name + "'");
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
  if (!v) throw Error(name + " is required");
  return *v;
}

std::optional<int> Arguments::integer(const std::string& name) const {
  const auto v = value(name);
  if (!v) return std::nullopt;
  std::size_t used = 0;
  int parsed = 0;
  try {
    parsed = std::stoi(*v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != v->size()) throw Error(name + " needs a whole number, not '" + *v + "'");
  return parsed;
}

std::optional<double> Arguments::number(const std::string& name) const {
  const auto v = value(name);
  if (!v) return std::nullopt;
  std::size_t used = 0;
  double parsed = 0;
  try {
    parsed = std::stod(*v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != v->size() || !std::isfinite(parsed)) throw Error(name + " needs a number, not '" + *v + "'");
  return parsed;
}

}  // namespace binpick::cli
