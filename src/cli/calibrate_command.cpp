// binpick calibrate rig | hand-eye: which calibration, then its own command.
#include "commands.hpp"

namespace binpick::cli {

void addCalibrateCommand(CLI::App& program, CommandTable& table) {
  CLI::App& calibrate =
      *program.add_subcommand("calibrate", "Calibrate the rig, or the camera relative to the robot (hand-eye)");
  calibrate.require_subcommand(1);
  addCalibrateRigCommand(calibrate, table);
  addCalibrateHandEyeCommand(calibrate, table);
}

}  // namespace binpick::cli
