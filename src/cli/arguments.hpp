#pragma once
// A subcommand's options. They are declared on its CLI::App with the add* functions below (what
// parses them and what its --help shows: one definition), and read after parsing through
// Arguments. A usage mistake found only by the command (an option its mode needs, missing) is
// thrown as a CLI11 error (missingOption), which the program reports as a usage error (exit 2).
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

namespace binpick::cli {

// `placeholder` names the value in the help (FILE, DIR, N, MM, ...); `help` says what it does and
// its default.
CLI::Option* addText(CLI::App& command, const std::string& name, const std::string& placeholder,
                     const std::string& help);
// A whole number; anything else is a usage error.
CLI::Option* addInteger(CLI::App& command, const std::string& name, const std::string& placeholder,
                        const std::string& help);
// A finite number; anything else is a usage error.
CLI::Option* addNumber(CLI::App& command, const std::string& name, const std::string& placeholder,
                       const std::string& help);
CLI::Option* addFlag(CLI::App& command, const std::string& name, const std::string& help);

// Options of one mode refused with those of another: giving one of `these` with one of `those`
// is a usage error naming both.
void refuseTogether(const std::vector<CLI::Option*>& these, const std::vector<CLI::Option*>& those);
// Every option of `group` (an option group, or a command).
std::vector<CLI::Option*> optionsOf(CLI::App& group);

class Arguments {
 public:
  // The options of `command`, parsed.
  explicit Arguments(const CLI::App& command) : command_(command) {}

  std::optional<std::string> value(const std::string& name) const;
  std::vector<std::string> values(const std::string& name) const;  // of an option taking several
  std::string required(const std::string& name) const;             // or throws missingOption
  bool flag(const std::string& name) const;
  std::optional<int> integer(const std::string& name) const;
  std::optional<double> number(const std::string& name) const;
  // Whether the command declares `name` (for helpers shared by commands with different options).
  bool declares(const std::string& name) const { return command_.get_option_no_throw(name) != nullptr; }

 private:
  const CLI::Option& option(const std::string& name) const;

  const CLI::App& command_;
};

// The usage error "NAME is required", for an option that the command's mode needs.
CLI::RequiredError missingOption(const std::string& name);

// The whole of `text` as an integer; throws core::Error naming `name` (an option, or a part
// of one such as "--projector width") otherwise.
int parseInteger(const std::string& name, const std::string& text);

}  // namespace binpick::cli
