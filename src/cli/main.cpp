// binpick: command-line entry to the bin-picking pipeline. `binpick --help` lists the subcommands,
// `binpick SUBCOMMAND --help` their options (commands.hpp), generated from the definitions that
// parse them.
#include "binpick/core/command_line.hpp"
#include "binpick/core/version.hpp"
#include "commands.hpp"

int main(int argc, char** argv) {
  CLI::App program(
      "binpick: structured-light capture, reconstruction, 6-DoF pose estimation of piled parts, "
      "calibration, the virtual cell, and a robot client for binpickd.",
      "binpick");
  binpick::core::applyCommandLineConventions(program, binpick::core::versionText());
  binpick::cli::CommandTable commands;
  binpick::cli::addCommands(program, commands);
  return binpick::core::runCommandLine(program, argc, argv, [&commands] { return commands.runSelected(); });
}
