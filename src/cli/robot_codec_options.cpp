// Robot codec options: declared and read the same way by every command that speaks the protocol.
#include "robot_codec_options.hpp"

namespace binpick::cli {

CLI::Option_group& addRobotCodecOptions(CLI::App& command) {
  CLI::Option_group& group = *command.add_option_group("Robot codec options");
  addText(group, "--framing", "NAME", "ascii (default) or binary");
  addText(group, "--orientation", "NAME", "quaternion (default), euler_zyx, fixed_xyz, rotation_vector or euler_xyz");
  addText(group, "--byte-order", "NAME", "Binary framing: big (default) or little");
  return group;
}

robot::CodecParams codecFromArguments(const Arguments& args) {
  robot::CodecParams codec;
  codec.framing = robot::framingFromName(args.value("--framing").value_or("ascii"));
  codec.byte_order = robot::byteOrderFromName(args.value("--byte-order").value_or("big"));
  if (const auto name = args.value("--orientation")) codec.orientation = core::orientationFromName(*name);
  codec.validate();
  return codec;
}

}  // namespace binpick::cli
