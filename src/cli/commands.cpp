#include "commands.hpp"

#include <stdexcept>

namespace binpick::cli {

CLI::App& CommandTable::add(CLI::App& parent, const std::string& name, const std::string& description, CommandRun run) {
  CLI::App* command = parent.add_subcommand(name, description);
  commands_.emplace_back(command, std::move(run));
  return *command;
}

int CommandTable::runSelected() const {
  // The deepest chosen subcommand: `calibrate rig` runs rig's function, not calibrate's.
  for (auto it = commands_.rbegin(); it != commands_.rend(); ++it) {
    if (it->first->parsed()) return it->second(Arguments(*it->first));
  }
  throw std::logic_error("no subcommand was chosen, though the program requires one");
}

void addCommands(CLI::App& program, CommandTable& table) {
  program.require_subcommand(1);
  addCaptureCommand(program, table);
  addReconstructCommand(program, table);
  addImportCaptureCommand(program, table);
  addDetectCommand(program, table);
  addSimulateCommand(program, table);
  addEvaluateCommand(program, table);
  addCalibrateCommand(program, table);
  addConvertCalibrationCommand(program, table);
  addGraspsCommand(program, table);
  addRobotClientCommand(program, table);
}

}  // namespace binpick::cli
