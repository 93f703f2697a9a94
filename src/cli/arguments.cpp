#include "arguments.hpp"

#include <cmath>

#include "binpick/core/error.hpp"

namespace binpick::cli {
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

double parseNumber(const std::string& name, const std::string& text) {
  return parseWhole<double>(name, text, "a number",
                            [](const std::string& t, std::size_t* used) { return std::stod(t, used); });
}

// CLI11 validators: an empty string accepts the value, anything else is the usage error's text.
std::string checkInteger(const std::string& text) {
  try {
    parseInteger("", text);
    return "";
  } catch (const core::Error&) {
    return "needs a whole number, not '" + text + "'";
  }
}

std::string checkNumber(const std::string& text) {
  try {
    parseNumber("", text);
    return "";
  } catch (const core::Error&) {
    return "needs a number, not '" + text + "'";
  }
}

}  // namespace

CLI::Option* addText(CLI::App& command, const std::string& name, const std::string& placeholder,
                     const std::string& help) {
  return command.add_option(name, help)->type_name(placeholder);
}

CLI::Option* addInteger(CLI::App& command, const std::string& name, const std::string& placeholder,
                        const std::string& help) {
  return addText(command, name, placeholder, help)->check(CLI::Validator(checkInteger, ""));
}

CLI::Option* addNumber(CLI::App& command, const std::string& name, const std::string& placeholder,
                       const std::string& help) {
  return addText(command, name, placeholder, help)->check(CLI::Validator(checkNumber, ""));
}

CLI::Option* addFlag(CLI::App& command, const std::string& name, const std::string& help) {
  return command.add_flag(name, help);
}

void refuseTogether(const std::vector<CLI::Option*>& these, const std::vector<CLI::Option*>& those) {
  for (CLI::Option* one : these) {
    for (CLI::Option* other : those) {
      if (one != other) one->excludes(other);
    }
  }
}

std::vector<CLI::Option*> optionsOf(CLI::App& group) {
  // An option group declares no --help of its own; a command's is not one of its modes' options.
  return group.get_options([&group](CLI::Option* option) { return option != group.get_help_ptr(); });
}

const CLI::Option& Arguments::option(const std::string& name) const {
  // A name not declared is a mistake of the command's own code, not of its user.
  const CLI::Option* declared = command_.get_option_no_throw(name);
  if (declared == nullptr) throw std::logic_error(command_.get_name() + " reads the undeclared option " + name);
  return *declared;
}

std::optional<std::string> Arguments::value(const std::string& name) const {
  const CLI::Option& declared = option(name);
  if (declared.count() == 0) return std::nullopt;
  return declared.results().front();
}

std::vector<std::string> Arguments::values(const std::string& name) const { return option(name).results(); }

std::string Arguments::required(const std::string& name) const {
  const auto v = value(name);
  if (!v) throw missingOption(name);
  return *v;
}

bool Arguments::flag(const std::string& name) const { return option(name).count() > 0; }

CLI::RequiredError missingOption(const std::string& name) { return CLI::RequiredError(name); }

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
  return parseNumber(name, *v);
}

}  // namespace binpick::cli
