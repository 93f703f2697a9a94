#pragma once
// Command-line options of the form `--name value` and `--flag`. Unknown or repeated options,
// and options missing their value, throw core::Error naming them.
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace binpick::cli {

class Arguments {
 public:
  // `valued`: options that take a value; `flags`: options that do not.
  Arguments(const std::vector<std::string>& args, const std::set<std::string>& valued,
            const std::set<std::string>& flags);

  std::optional<std::string> value(const std::string& name) const;
  std::string required(const std::string& name) const;
  bool flag(const std::string& name) const { return flags_.count(name) > 0; }
  std::optional<int> integer(const std::string& name) const;
  std::optional<double> number(const std::string& name) const;

 private:
  std::map<std::string, std::string> values_;
  std::set<std::string> flags_;
};

// The whole of `text` as an integer; throws core::Error naming `name` (an option, or a part
// of one such as "--projector width") otherwise.
int parseInteger(const std::string& name, const std::string& text);

}  // namespace binpick::cli
