// Binary framing: fixed-size messages of int32 fields in the configured byte order.
#include <array>
#include <cmath>

#include "binpick/io/error.hpp"
#include "robot_codec.hpp"

namespace binpick::robot::detail {

namespace {

constexpr std::size_t kReplyFields = kBinaryReplySize / 4;
constexpr std::size_t kFirstInteger = 2, kFirstPosition = 5, kFirstOrientation = 8;

// Byte by byte through uint32_t: the same on any host byte order, no aliasing tricks.
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

// round(value * scale), nothing when that does not fit an int32.
std::optional<int32_t> fixedPoint(double value, double scale) {
  const double scaled = std::round(value * scale);
  if (!(scaled >= -2147483648.0 && scaled <= 2147483647.0)) return std::nullopt;
  return static_cast<int32_t>(scaled);
}

// The pose fields of a reply, nothing when one of them overflows.
std::optional<std::array<int32_t, 7>> poseFields(const Eigen::Isometry3d& T_base_tool,
                                                 const CodecParams& params) {
  std::array<int32_t, 7> fields{};  // x, y, z, then up to 4 orientation values, unused 0
  const Eigen::Vector3d millimetres = T_base_tool.translation() * kMillimetresPerMetre;
  for (int axis = 0; axis < 3; ++axis) {
    const std::optional<int32_t> field = fixedPoint(millimetres[axis], params.position_scale);
    if (!field) return std::nullopt;
    fields[static_cast<std::size_t>(axis)] = *field;
  }
  std::vector<double> values = orientationValues(T_base_tool.linear(), params.orientation);
  if (params.orientation == Orientation::Quaternion) {  // on the int32 grid, pointing closest
    const std::array<double, 4> units = roundQuaternion(values, params.orientation_scale);
    for (std::size_t k = 0; k < 4; ++k) values[k] = units[k] / params.orientation_scale;
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::optional<int32_t> field = fixedPoint(values[i], params.orientation_scale);
    if (!field) return std::nullopt;
    fields[3 + i] = *field;
  }
  return fields;
}

Decoded failure(Status error, Command command, int32_t rawCommand, std::string detail) {
  Decoded decoded;
  decoded.error = error;
  decoded.command = command;
  decoded.raw_command = rawCommand;
  decoded.detail = std::move(detail);
  return decoded;
}

[[noreturn]] void malformed(const std::string& problem) {
  throw Error("malformed binary reply: " + problem);
}

Eigen::Isometry3d poseFromFields(const std::array<int32_t, kReplyFields>& fields,
                                 const CodecParams& params) {
  const std::size_t count = static_cast<std::size_t>(orientationValueCount(params.orientation));
  for (std::size_t i = kFirstOrientation + count; i < kReplyFields; ++i) {
    if (fields[i] != 0) malformed("an unused orientation field is not 0");
  }
  Eigen::Isometry3d T_base_tool = Eigen::Isometry3d::Identity();
  for (std::size_t axis = 0; axis < 3; ++axis) {
    T_base_tool.translation()[static_cast<Eigen::Index>(axis)] =
        fields[kFirstPosition + axis] / params.position_scale / kMillimetresPerMetre;
  }
  std::vector<double> values;
  for (std::size_t i = 0; i < count; ++i) {
    values.push_back(fields[kFirstOrientation + i] / params.orientation_scale);
  }
  try {
    T_base_tool.linear() = rotationFromValues(values, params.orientation);
  } catch (const Error& error) {
    malformed(error.what());
  }
  return T_base_tool;
}

}  // namespace

Decoded decodeBinaryRequest(const char* bytes, ByteOrder order) {
  const int32_t id = readInt32(bytes, order);
  const int32_t rawArgument = readInt32(bytes + 4, order);
  const auto command = static_cast<Command>(id);
  if (!isKnownCommand(command)) {
    return failure(Status::UnknownCommand, command, id, "unknown command id " + std::to_string(id));
  }
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

std::string encodeBinaryRequest(const Request& request, ByteOrder order) {
  int32_t argument = -1;  // none
  if (request.argument) {
    const std::optional<int32_t> number = parseNonNegativeInt32(*request.argument);
    if (!number) {
      throw Error("Request.argument '" + *request.argument +
                  "': the binary framing carries only an integer in [0, 2147483647]");
    }
    argument = *number;
  }
  std::string message;
  appendInt32(message, static_cast<int32_t>(request.command), order);
  appendInt32(message, argument, order);
  return message;
}

std::string encodeBinaryReply(const Reply& reply, const CodecParams& params) {
  std::array<int32_t, kReplyFields> fields{};
  fields[0] = static_cast<int32_t>(reply.command);
  fields[1] = static_cast<int32_t>(reply.status);
  for (std::size_t i = 0; i < reply.integers.size(); ++i)
    fields[kFirstInteger + i] = reply.integers[i];
  if (reply.T_base_tool) {
    const std::optional<std::array<int32_t, 7>> pose = poseFields(*reply.T_base_tool, params);
    if (pose) {
      std::copy(pose->begin(), pose->end(), fields.begin() + kFirstPosition);
    } else {
      fields = {};  // no integers and no pose, as the ASCII framing's "KEYWORD,8"
      fields[0] = static_cast<int32_t>(reply.command);
      fields[1] = static_cast<int32_t>(Status::BadMessage);
    }
  }
  std::string message;
  for (int32_t field : fields) appendInt32(message, field, params.byte_order);
  return message;
}

Reply decodeBinaryReply(const char* bytes, const CodecParams& params) {
  std::array<int32_t, kReplyFields> fields{};
  for (std::size_t i = 0; i < kReplyFields; ++i)
    fields[i] = readInt32(bytes + 4 * i, params.byte_order);
  Reply reply;
  reply.command = static_cast<Command>(fields[0]);
  const std::optional<Status> status = statusFromCode(fields[1]);
  if (!status) malformed("status " + std::to_string(fields[1]) + " is no status code");
  reply.status = *status;
  reply.integers.assign(fields.begin() + kFirstInteger, fields.begin() + kFirstPosition);
  if (reply.command == Command::NextPick && reply.status == Status::Ok) {
    reply.T_base_tool = poseFromFields(fields, params);
  } else {
    for (std::size_t i = kFirstPosition; i < kReplyFields; ++i) {
      if (fields[i] != 0) malformed("pose fields are set in a reply without a pose");
    }
  }
  try {
    checkReply(reply);
  } catch (const Error& error) {
    malformed(error.what());
  }
  return reply;
}

}  // namespace binpick::robot::detail
