// Binary framing: fixed-size messages of int32 fields in the configured byte order. POSE requests
// {command, x, y, z, o1, o2, o3, o4} are the only binary request longer than {command, argument}:
// the decoder learns the size from the command id, so that a robot that sends POSE and then PING
// stays in step.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "binpick/core/error.hpp"
#include "codec.hpp"

namespace binpick::robot::detail {

// Byte by byte through uint32_t: no aliasing tricks.
void appendInt32(std::string& out, int32_t value, ByteOrder order) {
  const auto bits = static_cast<uint32_t>(value);
  for (int i = 0; i < 4; ++i) {
    const int shift = order == ByteOrder::Big ? 24 - 8 * i : 8 * i;
    out.push_back(static_cast<char>((bits >> shift) & 0xffu));
  }
}

int32_t readInt32(const char* bytes, ByteOrder order) {
  uint32_t bits = 0;
  for (int i = 0; i < 4; ++i) {
    const int shift = order == ByteOrder::Big ? 24 - 8 * i : 8 * i;
    bits |= static_cast<uint32_t>(static_cast<unsigned char>(bytes[i])) << shift;
  }
  return static_cast<int32_t>(bits);  // two's complement (guaranteed since C++20, universal)
}

std::optional<int32_t> fixedPoint(double value, double scale) {
  const double scaled = std::round(value * scale);
  if (!(scaled >= -2147483648.0 && scaled <= 2147483647.0)) return std::nullopt;
  return static_cast<int32_t>(scaled);
}

namespace {

constexpr std::size_t kReplyFields = kBinaryReplySize / 4;
constexpr std::size_t kFirstInteger = 2, kFirstPosition = 5;

Decoded failure(Status error, Command command, int32_t rawCommand, std::string detail) {
  Decoded decoded;
  decoded.error = error;
  decoded.command = command;
  decoded.raw_command = rawCommand;
  decoded.detail = std::move(detail);
  return decoded;
}

[[noreturn]] void malformed(const std::string& problem) { throw core::Error("malformed binary reply: " + problem); }

constexpr const char* kWhichConvention = "is --orientation the cell's robot.orientation?";

std::string fieldsText(const int32_t* fields, std::size_t count) {
  std::string text;
  for (std::size_t i = 0; i < count; ++i) text += (i == 0 ? "" : ", ") + std::to_string(fields[i]);
  return text;
}

// The binary framing has room for 4 orientation values whatever the convention, so a pick sent
// in another convention keeps its layout and only its values tell: a 3-value convention leaves
// the fourth field 0, and a quaternion is of unit length up to its grid (each value within one
// unit of 1 / orientation_scale, so the length within two). Either read in the other convention
// is almost always caught here; a quaternion whose z is 0 can still pass for three angles.
void requireOrientationOfConvention(const BinaryPoseFields& pose, const CodecParams& params) {
  const int32_t* orientation = pose.data() + 3;
  if (params.orientation != core::Orientation::Quaternion) {
    if (orientation[3] == 0) return;
    malformed("NEXT's fourth orientation field, unused in the " + core::orientationName(params.orientation) +
              " convention (3 values), holds " + std::to_string(orientation[3]) + ": " + kWhichConvention);
  }
  Eigen::Vector4d units;
  for (int k = 0; k < 4; ++k) units[k] = orientation[k];
  const double length = units.norm() / params.orientation_scale;
  if (length == 0.0) return;  // a zero quaternion: poseFromBinaryFields names it
  const double tolerance = 2.0 / params.orientation_scale;
  if (std::abs(length - 1.0) <= tolerance) return;
  char measured[32];
  std::snprintf(measured, sizeof(measured), "%.6g", length);
  malformed("NEXT's quaternion (fields " + fieldsText(orientation, 4) + ") has length " + measured +
            ", not 1: " + kWhichConvention);
}

}  // namespace

Decoded decodeBinaryRequest(const char* bytes, const CodecParams& params) {
  const int32_t id = readInt32(bytes, params.byte_order);
  const auto command = static_cast<Command>(id);
  if (!isKnownCommand(command)) {
    return failure(Status::UnknownCommand, command, id, "unknown command id " + std::to_string(id));
  }
  if (command == Command::Pose) return decodeBinaryPoseRequest(bytes, params);
  const int32_t rawArgument = readInt32(bytes + 4, params.byte_order);
  // Robots write both fields whatever the command: an argument to one taking none is dropped.
  std::optional<std::string> argument;
  if (rawArgument >= 0 && takesArgument(command)) argument = std::to_string(rawArgument);
  const std::string problem = argumentProblem(command, argument);
  if (!problem.empty()) return failure(Status::BadMessage, command, id, problem);
  Decoded decoded;
  decoded.command = command;
  decoded.raw_command = id;
  decoded.request = Request{command, argument};
  return decoded;
}

std::string encodeBinaryRequest(const Request& request, const CodecParams& params) {
  if (request.command == Command::Pose) return encodeBinaryPoseRequest(request, params);
  int32_t argument = -1;  // none
  if (request.argument) {
    const std::optional<int32_t> number = parseNonNegativeInt32(*request.argument);
    if (!number) {
      throw core::Error("Request.argument '" + *request.argument +
                        "': the binary framing carries only an integer in [0, 2147483647]");
    }
    argument = *number;
  }
  std::string message;
  appendInt32(message, static_cast<int32_t>(request.command), params.byte_order);
  appendInt32(message, argument, params.byte_order);
  return message;
}

std::optional<std::string> encodeBinaryReply(const Reply& reply, const CodecParams& params) {
  std::array<int32_t, kReplyFields> fields{};
  fields[0] = static_cast<int32_t>(reply.command);
  fields[1] = static_cast<int32_t>(reply.status);
  for (std::size_t i = 0; i < reply.integers.size(); ++i) fields[kFirstInteger + i] = reply.integers[i];
  if (reply.T_base_tool) {
    const std::optional<BinaryPoseFields> pose = binaryPoseFields(*reply.T_base_tool, params);
    if (!pose) return std::nullopt;
    std::copy(pose->begin(), pose->end(), fields.begin() + kFirstPosition);
  }
  std::string message;
  for (int32_t field : fields) appendInt32(message, field, params.byte_order);
  return message;
}

Reply decodeBinaryReply(const char* bytes, const CodecParams& params) {
  std::array<int32_t, kReplyFields> fields{};
  for (std::size_t i = 0; i < kReplyFields; ++i) fields[i] = readInt32(bytes + 4 * i, params.byte_order);
  Reply reply;
  reply.command = static_cast<Command>(fields[0]);
  const std::optional<Status> status = statusFromCode(fields[1]);
  if (!status) malformed("status " + std::to_string(fields[1]) + " is no status code");
  reply.status = *status;
  reply.integers.assign(fields.begin() + kFirstInteger, fields.begin() + kFirstPosition);
  if (reply.command == Command::NextPick && reply.status == Status::Ok) {
    BinaryPoseFields pose{};
    std::copy(fields.begin() + kFirstPosition, fields.end(), pose.begin());
    requireOrientationOfConvention(pose, params);
    std::string problem;
    reply.T_base_tool = poseFromBinaryFields(pose, params, problem);
    if (!reply.T_base_tool) malformed(problem);
  } else {
    for (std::size_t i = kFirstPosition; i < kReplyFields; ++i) {
      if (fields[i] != 0) malformed("pose fields are set in a reply without a pose");
    }
  }
  try {
    checkReply(reply);
  } catch (const core::Error& error) {
    malformed(error.what());
  }
  return reply;
}

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
    throw core::Error(
        "Request.T_base_flange: a value does not fit the binary framing's int32 fields "
        "(position_scale, orientation_scale)");
  }
  std::string message;
  appendInt32(message, static_cast<int32_t>(Command::Pose), params.byte_order);
  for (int32_t field : *fields) appendInt32(message, field, params.byte_order);
  return message;
}

}  // namespace binpick::robot::detail
