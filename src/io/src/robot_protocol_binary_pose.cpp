// Binary POSE requests: {command, x, y, z, o1, o2, o3, o4}, the only binary request longer than
// {command, argument}. The decoder learns the size from the command id, so that a robot that
// sends POSE and then PING stays in step.
#include "binpick/io/error.hpp"
#include "robot_codec.hpp"

namespace binpick::robot::detail {

namespace {

Decoded badPose(std::string detail) {
  Decoded decoded;
  decoded.error = Status::BadMessage;
  decoded.command = Command::Pose;
  decoded.raw_command = static_cast<int32_t>(Command::Pose);
  decoded.detail = "POSE: " + std::move(detail);
  return decoded;
}

}  // namespace

std::size_t binaryRequestSize(int32_t id) {
  return id == static_cast<int32_t>(Command::Pose) ? kBinaryPoseRequestSize : kBinaryRequestSize;
}

Decoded decodeBinaryPoseRequest(const char* bytes, const CodecParams& params) {
  BinaryPoseFields fields{};
  for (std::size_t i = 0; i < kBinaryPoseFields; ++i) {
    fields[i] = readInt32(bytes + 4 * (i + 1), params.byte_order);
  }
  std::string problem;
  std::optional<Eigen::Isometry3d> T_base_flange = poseFromBinaryFields(fields, params, problem);
  if (!T_base_flange) return badPose(problem);
  Decoded decoded;
  decoded.command = Command::Pose;
  decoded.raw_command = static_cast<int32_t>(Command::Pose);
  decoded.request = Request{Command::Pose, std::nullopt, T_base_flange};
  return decoded;
}

std::string encodeBinaryPoseRequest(const Request& request, const CodecParams& params) {
  const std::optional<BinaryPoseFields> fields = binaryPoseFields(*request.T_base_flange, params);
  if (!fields) {
    throw Error("Request.T_base_flange: a value does not fit the binary framing's int32 fields "
                "(position_scale, orientation_scale)");
  }
  std::string message;
  appendInt32(message, static_cast<int32_t>(Command::Pose), params.byte_order);
  for (int32_t field : *fields) appendInt32(message, field, params.byte_order);
  return message;
}

}  // namespace binpick::robot::detail
