#pragma once
// The conventions of binpick's programs (binpick, binpickd) on the command line, on CLI11: the
// options a program declares are what it parses and what its help shows, so the two cannot drift.
//   --help, -h    the usage generated from the declarations, on stdout; exit 0 (for the program
//                 and for every subcommand);
//   --version     the version text given (the project version and git revision: version.hpp);
//                 exit 0;
//   usage error   an unknown option, a missing or malformed value, a missing subcommand, options
//                 that exclude each other (or a CLI::ParseError the run throws: an option its
//                 mode needs, missing): one line on stderr naming it, with a hint to --help; exit 2;
//   run error     core::Error (or any exception) while running: one line on stderr; exit 1.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace binpick::core {

inline constexpr int kExitRunError = 1;
inline constexpr int kExitUsageError = 2;

// A program's top-level app with the conventions above: version flag, help layout, and the
// one-line failure message.
void applyCommandLineConventions(CLI::App& program, const std::string& version);

// "binpick calibrate rig": the program and the subcommands selected on its command line, for
// messages that name where they come from.
std::string commandPath(const CLI::App& program);

// Parses argv with `program` and calls `run` when parsing succeeded, returning the exit code as
// above (run's own code when it returns).
int runCommandLine(CLI::App& program, int argc, const char* const* argv, const std::function<int()>& run);

}  // namespace binpick::core
