#pragma once
// The subcommands of `binpick`, one file each. Each add*Command declares its subcommand and its
// options on the program (what parses them and what `--help` shows) and registers the function
// that runs it on the parsed options. A run returns the exit code; bad input throws core::Error
// (one line, exit 1) and a usage mistake only the command can see throws a CLI11 error (exit 2).
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "arguments.hpp"

namespace binpick::cli {

using CommandRun = std::function<int(const Arguments&)>;

// The subcommands that run something, each with its run function.
class CommandTable {
 public:
  // Adds subcommand `name` under `parent` (the program, or a group such as `calibrate`).
  CLI::App& add(CLI::App& parent, const std::string& name, const std::string& description, CommandRun run);
  // Runs the subcommand chosen on the parsed command line.
  int runSelected() const;

 private:
  std::vector<std::pair<const CLI::App*, CommandRun>> commands_;
};

// The whole program: every subcommand below, declared on `program`.
void addCommands(CLI::App& program, CommandTable& table);

void addCaptureCommand(CLI::App& program, CommandTable& table);
void addReconstructCommand(CLI::App& program, CommandTable& table);
void addImportCaptureCommand(CLI::App& program, CommandTable& table);  // another rig's images
void addDetectCommand(CLI::App& program, CommandTable& table);
void addSimulateCommand(CLI::App& program, CommandTable& table);
void addEvaluateCommand(CLI::App& program, CommandTable& table);
void addCalibrateCommand(CLI::App& program, CommandTable& table);  // rig | hand-eye
void addCalibrateRigCommand(CLI::App& calibrate, CommandTable& table);
void addCalibrateHandEyeCommand(CLI::App& calibrate, CommandTable& table);  // from a file, or --listen
void addConvertCalibrationCommand(CLI::App& program, CommandTable& table);  // another tool's calibration
void addGraspsCommand(CLI::App& program, CommandTable& table);              // grasps generated from a part model
void addRobotClientCommand(CLI::App& program, CommandTable& table);

}  // namespace binpick::cli
