#pragma once
// How the robot's messages are framed on the command line, shared by `robot-client` and the guided
// hand-eye session, in the option group "Robot codec options":
//   --framing ascii|binary  --orientation NAME  --byte-order big|little
// They must match binpickd's robot_protocol settings (docs/robot-protocol.md).
#include <CLI/CLI.hpp>

#include "arguments.hpp"
#include "binpick/robot/protocol.hpp"

namespace binpick::cli {

// Declares the options above on `command`; returns their group.
CLI::Option_group& addRobotCodecOptions(CLI::App& command);

// The codec the options describe, validated; throws core::Error naming the bad name.
robot::CodecParams codecFromArguments(const Arguments& args);

}  // namespace binpick::cli
