// The `picking:`, `robot:`, `limits:` and `artefacts:` sections.
#include "binpick/core/orientation.hpp"
#include "binpick/core/pose_yaml.hpp"
#include "config_sections.hpp"

namespace binpick::cell {
namespace {

// A setting naming one of a few choices: the parser's complaint, prefixed with the key.
template <typename Parse>
auto choice(const core::YamlSection& section, const char* key, const std::string& text, Parse parse) {
  try {
    return parse(text);
  } catch (const core::Error& e) {
    section.fail(key, e.what());
  }
}

picking::GripperParams readGripper(core::YamlSection s) {
  picking::GripperParams gripper;
  std::string type = picking::gripperTypeName(gripper.type);
  s.read("type", type);
  s.read("cup_diameter", gripper.cup_diameter);
  s.read("cup_length", gripper.cup_length);
  s.read("seal_tolerance", gripper.seal_tolerance);
  s.read("max_lean_deg", gripper.max_lean_deg);
  s.read("nose_angle_deg", gripper.nose_angle_deg);
  s.read("stroke", gripper.stroke);
  s.read("finger_width", gripper.finger_width);
  s.read("finger_depth", gripper.finger_depth);
  s.read("finger_thickness", gripper.finger_thickness);
  s.read("tool_radius", gripper.tool_radius);
  s.read("tool_length", gripper.tool_length);
  s.finish();
  gripper.type = choice(s, "type", type, picking::gripperTypeFromName);
  return gripper;
}

picking::RankWeights readRanking(core::YamlSection s) {
  picking::RankWeights weights;
  s.read("free", weights.free);
  s.read("height", weights.height);
  s.read("coverage", weights.coverage);
  s.read("upright", weights.upright);
  s.read("clearance", weights.clearance);
  s.read("quality", weights.quality);
  s.finish();
  return weights;
}

}  // namespace

picking::PickParams readPicking(core::YamlSection s) {
  picking::PickParams params;
  core::YamlSection bin = s.child("bin");
  bin.read("length", params.bin.length);
  bin.read("width", params.bin.width);
  bin.read("wall_height", params.bin.wall_height);
  if (bin.has("T_base_bin"))
    params.bin.T_base_bin = core::readPose(bin.child("T_base_bin"));
  else
    bin.skip("T_base_bin");
  bin.finish();
  if (s.has("tool_radius")) s.fail("tool_radius", "moved to picking.gripper.tool_radius");
  params.gripper = readGripper(s.child("gripper"));
  s.read("approach_distance", params.approach_distance);
  s.read("wall_clearance", params.wall_clearance);
  s.read("max_tilt_deg", params.max_tilt_deg);
  s.read("continuous_symmetry_steps", params.continuous_symmetry_steps);
  s.read("avoid_radius", params.avoid_radius);
  s.read("collision_margin", params.collision_margin);
  s.read("finger_clearance", params.finger_clearance);
  s.read("clearance_cap", params.clearance_cap);
  s.read("cover_radius", params.cover_radius);
  s.read("cover_height", params.cover_height);
  params.ranking = readRanking(s.child("ranking"));
  std::string order = "best_rank";
  s.read("order", order);
  s.finish();
  params.order = choice(s, "order", order, picking::pickOrderFromName);
  return params;
}

robot::RobotServerParams readRobot(core::YamlSection s) {
  robot::RobotServerParams params;
  s.read("bind_address", params.bind_address);
  s.read("port", params.port);
  s.read("allowed_clients", params.allowed_clients);
  s.read("max_clients", params.max_clients);
  s.read("idle_timeout_ms", params.idle_timeout_ms);
  s.read("keepalive_idle_s", params.keepalive_idle_s);
  s.read("keepalive_interval_s", params.keepalive_interval_s);
  s.read("keepalive_count", params.keepalive_count);
  s.read("bad_request_log_interval_ms", params.bad_request_log_interval_ms);
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
  codec.orientation = choice(s, "orientation", orientation, core::orientationFromName);
  return params;
}

CycleLimits readLimits(core::YamlSection s) {
  CycleLimits limits;
  s.read("capture_timeout_ms", limits.capture_timeout_ms);
  s.read("processing_timeout_ms", limits.processing_timeout_ms);
  s.read("max_picks", limits.max_picks);
  s.read("min_pick_coverage", limits.min_pick_coverage);
  s.read("empty_bin_max_points", limits.empty_bin_max_points);
  s.read("empty_bin_min_height", limits.empty_bin_min_height);
  s.read("avoid_cycles", limits.avoid_cycles);
  s.read("trim_memory_after_cycle", limits.trim_memory_after_cycle);
  s.finish();
  return limits;
}

std::optional<ArtefactParams> readArtefacts(core::YamlSection s, const PathResolver& resolve) {
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
