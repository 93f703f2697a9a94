#include "binpick/core/command_line.hpp"

#include <algorithm>
#include <exception>
#include <iostream>
#include <memory>

namespace binpick::core {
namespace {

// CLI11's messages can span lines ("The following arguments were not expected: ..."): one line.
std::string oneLine(std::string text) {
  for (char& c : text) {
    if (c == '\n') c = ' ';
  }
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

// CLI11's help, with the options an option excludes left out of its line (modes refuse each
// other's options, and listing them all would bury the descriptions; the refusal itself names
// both options), and an option group shown as a heading ("Board options:") over its options.
class ConventionsFormatter : public CLI::Formatter {
 public:
  std::string make_expanded(const CLI::App* sub) const override {
    if (!sub->get_name().empty()) return CLI::Formatter::make_expanded(sub);
    std::string text = "\n" + sub->get_group() + ":\n";
    for (const CLI::Option* option : sub->get_options()) {
      if (option != sub->get_help_ptr() && option->nonpositional() && !option->get_group().empty())
        text += make_option(option, false);
    }
    return text;
  }

  std::string make_option_opts(const CLI::Option* option) const override {
    std::string text = CLI::Formatter::make_option_opts(option);
    const auto excludes = text.find(" " + get_label("Excludes") + ":");
    if (excludes != std::string::npos) text.erase(excludes);
    return text;
  }
};

}  // namespace

std::string commandPath(const CLI::App& program) {
  std::string path = program.get_name();
  const CLI::App* app = &program;
  for (;;) {
    const auto selected = app->get_subcommands();
    if (selected.empty()) return path;
    app = selected.front();
    path += " " + app->get_name();
  }
}

void applyCommandLineConventions(CLI::App& program, const std::string& version) {
  program.set_version_flag("--version", program.get_name() + " " + version,
                           "Print the version (and git revision) and exit");
  auto formatter = std::make_shared<ConventionsFormatter>();
  formatter->column_width(42);
  program.formatter(formatter);
  program.failure_message([](const CLI::App* app, const CLI::Error& error) {
    const std::string path = commandPath(*app);
    return path + ": " + oneLine(error.what()) + " (see '" + path + " --help')\n";
  });
}

int runCommandLine(CLI::App& program, int argc, const char* const* argv, const std::function<int()>& run) {
  try {
    program.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    // Help and version are "errors" to CLI11 that exit 0, printed on stdout.
    if (error.get_exit_code() == 0) return program.exit(error, std::cout, std::cerr);
    // CLI11 checks the required options before the arguments it did not expect, so a mistyped
    // option would be reported as the option it was meant to be, missing: name it instead.
    std::vector<std::string> unexpected = program.remaining(true);
    // (CLI11's own ExtrasError lists them backwards: it is made here in their order.)
    if (!unexpected.empty()) {
      std::reverse(unexpected.begin(), unexpected.end());
      program.exit(CLI::ExtrasError(unexpected), std::cout, std::cerr);
    } else {
      program.exit(error, std::cout, std::cerr);
    }
    return kExitUsageError;
  }
  try {
    return run();
  } catch (const CLI::ParseError& error) {
    // A usage mistake only the command can see (an option its mode needs, missing).
    program.exit(error, std::cout, std::cerr);
    return kExitUsageError;
  } catch (const std::exception& error) {
    std::cerr << commandPath(program) << ": " << error.what() << "\n";
    return kExitRunError;
  }
}

}  // namespace binpick::core
