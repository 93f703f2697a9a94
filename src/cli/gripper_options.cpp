// Gripper options: declared and read the same way by every command that grasps.
#include "gripper_options.hpp"

namespace binpick::cli {
namespace {

const std::vector<std::string> kSuctionOnly = {"--cup-diameter", "--seal-tolerance", "--nose-angle"};
const std::vector<std::string> kParallelOnly = {"--stroke", "--finger-width", "--finger-depth"};

}  // namespace

std::vector<CLI::Option*> addGripperOptions(CLI::App& command, const std::string& gripper_help) {
  std::vector<CLI::Option*> options = {addText(command, "--gripper", "TYPE", gripper_help)};
  CLI::Option_group& group = *command.add_option_group("Gripper options");
  addNumber(group, "--cup-diameter", "M",
            "Suction: cup diameter (default 0.006; simulate --empty-bin: the cup chosen for the part)");
  addNumber(group, "--seal-tolerance", "M", "Suction: surface deviation the cup seals on (default 0.0008)");
  addNumber(group, "--nose-angle", "DEG", "Suction: degrees between the cup's axis and the tool body's (default 0)");
  addNumber(group, "--stroke", "M", "Parallel: widest opening (default 0.08)");
  addNumber(group, "--finger-width", "M", "Parallel: finger width (default 0.012)");
  addNumber(group, "--finger-depth", "M", "Parallel: finger depth along the approach (default 0.02)");
  addNumber(group, "--tool-radius", "M", "Radius of the tool body (default 0.015)");
  addNumber(group, "--tool-length", "M", "Length of the tool body (default 0.15)");
  for (CLI::Option* option : optionsOf(group)) options.push_back(option);
  return options;
}

picking::GripperParams gripperFromArguments(const Arguments& args) {
  picking::GripperParams gripper;
  gripper.type = picking::gripperTypeFromName(args.value("--gripper").value_or("suction"));
  const bool suction = gripper.type == picking::GripperType::Suction;
  for (const std::string& name : suction ? kParallelOnly : kSuctionOnly) {
    if (args.value(name)) throw CLI::ExcludesError(name, "--gripper " + picking::gripperTypeName(gripper.type));
  }
  const auto set = [&args](const char* name, double& value) {
    if (const auto number = args.number(name)) value = *number;
  };
  set("--cup-diameter", gripper.cup_diameter);
  set("--seal-tolerance", gripper.seal_tolerance);
  set("--nose-angle", gripper.nose_angle_deg);
  set("--stroke", gripper.stroke);
  set("--finger-width", gripper.finger_width);
  set("--finger-depth", gripper.finger_depth);
  set("--tool-radius", gripper.tool_radius);
  set("--tool-length", gripper.tool_length);
  gripper.validate();
  return gripper;
}

}  // namespace binpick::cli
