#pragma once
// The gripper on the command line, shared by `grasps` and `simulate --empty-bin`: --gripper
// suction|parallel and, in the option group "Gripper options", its sizes in metres:
//   suction   --cup-diameter M  --seal-tolerance M
//   parallel  --stroke M  --finger-width M  --finger-depth M
//   both      --tool-radius M  --tool-length M
// A size of the other type of gripper is refused as a usage error rather than ignored.
#include <CLI/CLI.hpp>
#include <vector>

#include "arguments.hpp"
#include "binpick/picking/gripper.hpp"

namespace binpick::cli {

// Declares --gripper (with `gripper_help`) and the sizes on `command`; returns them all.
std::vector<CLI::Option*> addGripperOptions(CLI::App& command, const std::string& gripper_help);

// The gripper the options describe (suction without --gripper), validated. Throws a usage error
// for a size of the other type, core::Error for a bad name or size.
picking::GripperParams gripperFromArguments(const Arguments& args);

}  // namespace binpick::cli
