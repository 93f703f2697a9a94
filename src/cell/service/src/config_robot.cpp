// The `picking:`, `robot:`, `limits:` and `artefacts:` sections.
#include "config_pose.hpp"
#include "config_sections.hpp"
#include "binpick/io/robot_orientation.hpp"

namespace binpick::cell {
namespace {

// A setting naming one of a few choices: the parser's complaint, prefixed with the key.
template <typename Parse>
auto choice(const YamlSection& section, const char* key, const std::string& text, Parse parse) {
  try {
    return parse(text);
  } catch (const Error& e) {
    section.fail(key, e.what());
  }
}

}  // namespace

PickParams readPicking(YamlSection s) {
  PickParams params;
  YamlSection bin = s.child("bin");
  bin.read("length", params.bin.length);
  bin.read("width", params.bin.width);
  bin.read("wall_height", params.bin.wall_height);
  if (bin.has("T_base_bin")) params.bin.T_base_bin = readPose(bin.child("T_base_bin"));
  else bin.skip("T_base_bin");
  bin.finish();
  s.read("approach_distance", params.approach_distance);
  s.read("tool_radius", params.gripper.tool_radius);
  s.read("wall_clearance", params.wall_clearance);
  s.read("max_tilt_deg", params.max_tilt_deg);
  s.read("continuous_symmetry_steps", params.continuous_symmetry_steps);
  s.read("avoid_radius", params.avoid_radius);
  std::string order = "highest_first";
  s.read("order", order);
  s.finish();
  params.order = choice(s, "order", order, pickOrderFromName);
  return params;
}

RobotServerParams readRobot(YamlSection s) {
  RobotServerParams params;
  s.read("bind_address", params.bind_address);
  s.read("port", params.port);
  s.read("allowed_clients", params.allowed_clients);
  s.read("max_clients", params.max_clients);
  std::string framing = "ascii", orientation = "quaternion", byte_order = "big";
  s.read("framing", framing);
  s.read("orientation", orientation);
  s.read("byte_order", byte_order);
  robot::CodecParams& codec = params.codec;
  s.read("max_line_length", codec.max_line_length);
  s.read("position_decimals", codec.position_decimals);
  s.read("orientation_decimals", codec.orientation_decimals);
  s.read("position_scale", codec.position_scale);
  s.read("orientation_scale", codec.orientation_scale);
  s.finish();
  codec.framing = choice(s, "framing", framing, robot::framingFromName);
  codec.byte_order = choice(s, "byte_order", byte_order, robot::byteOrderFromName);
  codec.orientation = choice(s, "orientation", orientation, robot::orientationFromName);
  return params;
}

CycleLimits readLimits(YamlSection s) {
  CycleLimits limits;
  s.read("capture_timeout_ms", limits.capture_timeout_ms);
  s.read("processing_timeout_ms", limits.processing_timeout_ms);
  s.read("max_picks", limits.max_picks);
  s.read("min_pick_coverage", limits.min_pick_coverage);
  s.read("empty_bin_max_points", limits.empty_bin_max_points);
  s.read("empty_bin_min_height", limits.empty_bin_min_height);
  s.read("avoid_cycles", limits.avoid_cycles);
  s.finish();
  return limits;
}

std::optional<ArtefactParams> readArtefacts(YamlSection s, const PathResolver& resolve) {
  ArtefactParams params;
  s.read("directory", params.directory);
  s.read("max_cycles", params.max_cycles);
  s.read("max_bytes", params.max_bytes);
  s.read("capture", params.capture);
  s.read("cloud", params.cloud);
  s.read("detections", params.detections);
  s.read("overlay", params.overlay);
  s.read("threads", params.threads);
  s.finish();
  if (params.directory.empty()) return std::nullopt;  // saving is off
  params.directory = resolve(params.directory);
  return params;
}

}  // namespace binpick::cell
