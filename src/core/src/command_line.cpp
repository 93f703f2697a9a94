#include "binpick/core/command_line.hpp"

#include <exception>
#include <iostream>

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
  program.get_formatter()->column_width(32);
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
    const int code = program.exit(error, std::cout, std::cerr);
    return code == 0 ? 0 : kExitUsageError;
  }
  try {
    return run();
  } catch (const std::exception& error) {
    std::cerr << commandPath(program) << ": " << error.what() << "\n";
    return kExitRunError;
  }
}

}  // namespace binpick::core
