// binpickd: the bin-picking cell service. It serves robot controllers over TCP: capture (camera +
// projector, or replay of recorded captures), reconstruct, detect, plan picks, send them.
// The command line (CLI11; `binpickd --help`) follows binpick's conventions (core/command_line.hpp).
// --check loads and prepares everything (writing the model caches), then exits: 0 when the
// settings are good.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <iostream>
#include <string>

#include "binpick/cell/cell_config.hpp"
#include "binpick/cell/cell_setup.hpp"
#include "binpick/core/command_line.hpp"
#include "binpick/core/version.hpp"
#include "daemon.hpp"

namespace {

struct CommandLine {
  binpick::daemon::DaemonOptions options;
  bool check = false;
  bool verbose = false;
};

void declareOptions(CLI::App& program, CommandLine& line) {
  program.add_option("--config", line.options.config_path, "The settings file (binpickd.yaml; docs/binpickd.md)")
      ->type_name("FILE")
      ->required();
  program
      .add_option("--port", line.options.port_override,
                  "Listen for robots on this TCP port instead of the settings' robot.port (0: any free port)")
      ->type_name("N")
      ->check(CLI::Range(0, 65535));
  program.add_option("--port-file", line.options.port_file, "Write the bound port to this file once listening")
      ->type_name("FILE");
  program.add_flag("--check", line.check,
                   "Load and prepare everything (settings, calibration, models and their caches), print a "
                   "summary and exit: 0 when the settings are good");
  program.add_flag("--verbose", line.verbose, "Log debug messages too");
}

int check(const std::string& path) {
  const auto setup = binpick::cell::prepareCell(binpick::cell::loadCellConfig(path));
  std::cout << path << ": " << setup->recipes.size() << " recipe(s) ready in " << static_cast<int>(setup->prepare_ms)
            << " ms" << (setup->reconstructor ? "" : "; calibration: " + setup->calibration_problem) << "\n";
  return 0;
}

int run(const CommandLine& line) {
  // One stream for the journal (stderr, like every component's logger); journald adds the time.
  spdlog::set_default_logger(spdlog::stderr_color_mt("binpickd"));
  spdlog::set_pattern("[%l] %n: %v");
  if (line.verbose) spdlog::set_level(spdlog::level::debug);
  if (line.check) return check(line.options.config_path);
  return binpick::daemon::runDaemon(line.options);
}

}  // namespace

int main(int argc, char** argv) {
  binpick::daemon::blockStopAndReloadSignals();  // before any thread starts
  CLI::App program(
      "binpickd: the bin-picking cell service. Robot controllers connect over TCP, trigger a cycle "
      "(capture, reconstruct, detect, plan grasps) and fetch picks (docs/robot-protocol.md).",
      "binpickd");
  binpick::core::applyCommandLineConventions(program, binpick::core::versionText());
  CommandLine line;
  declareOptions(program, line);
  return binpick::core::runCommandLine(program, argc, argv, [&line] { return run(line); });
}
