// ASCII replies: "KEYWORD,status[,integers...][,x,y,z,orientation...]\r\n".
#include <array>
#include <charconv>
#include <cmath>
#include <vector>

#include "binpick/io/error.hpp"
#include "robot_codec.hpp"

namespace binpick::robot::detail {

namespace {

// How many decimals a reply gives up, in turn, when it is too long at full precision: the
// orientation first (a quaternion's fifth decimal moves a point 200 mm from the flange by
// ~2 um, a position's second decimal by 10 um), and never more than these.
struct PrecisionDrop {
  int position, orientation;
};
constexpr std::array<PrecisionDrop, 4> kPrecisionDrops = {{{0, 0}, {0, 1}, {1, 1}, {1, 2}}};

std::optional<std::string> poseText(const Eigen::Isometry3d& T_base_tool, const CodecParams& params,
                                    PrecisionDrop drop) {
  return asciiPoseText(T_base_tool, params.orientation,
                       std::max(0, params.position_decimals - drop.position),
                       std::max(0, params.orientation_decimals - drop.orientation));
}

std::string badMessageLine(Command command) {
  return std::string(commandKeyword(command)) + "," +
         std::to_string(static_cast<int32_t>(Status::BadMessage)) + "\r\n";
}

// --- decoding

[[noreturn]] void malformed(std::string_view line, const std::string& problem) {
  std::string shown(line.substr(0, 100));
  for (char& c : shown) {
    if (c < 0x20 || c > 0x7e) c = '?';  // the message goes to logs and terminals
  }
  throw Error("malformed reply '" + shown + "': " + problem);
}

template <typename Number>
std::optional<Number> parseNumber(std::string_view text) {
  Number value{};
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || result.ec != std::errc() || result.ptr != text.data() + text.size()) {
    return std::nullopt;
  }
  return value;
}

Command replyCommand(std::string_view line, std::string_view keyword) {
  if (const std::optional<Command> command = commandFromKeyword(keyword)) return *command;
  if (keyword == kUnknownKeyword) return kUnknownAsciiCommand;
  malformed(line, "unknown keyword");
}

Eigen::Isometry3d parsePose(std::string_view line, const std::vector<std::string_view>& fields,
                            Orientation orientation) {
  std::vector<double> values;
  for (std::string_view field : fields) {
    const std::optional<double> value = parseFiniteNumber(field);
    if (!value) malformed(line, "a pose value is no finite number");
    values.push_back(*value);
  }
  std::string problem;
  const std::optional<Eigen::Isometry3d> T_base_tool =
      poseFromWireValues(values, orientation, problem);
  if (!T_base_tool) malformed(line, problem);
  return *T_base_tool;
}

}  // namespace

std::string encodeAsciiReply(const Reply& reply, const CodecParams& params) {
  std::string head = std::string(commandKeyword(reply.command)) + "," +
                     std::to_string(static_cast<int32_t>(reply.status));
  for (int32_t integer : reply.integers) head += "," + std::to_string(integer);
  if (!reply.T_base_tool) {
    const std::string line = head + "\r\n";
    return line.size() <= params.max_line_length ? line : badMessageLine(reply.command);
  }
  for (const PrecisionDrop& drop : kPrecisionDrops) {
    const std::optional<std::string> pose = poseText(*reply.T_base_tool, params, drop);
    if (!pose) break;
    const std::string line = head + *pose + "\r\n";
    if (line.size() <= params.max_line_length) return line;
  }
  return badMessageLine(reply.command);
}

Reply decodeAsciiReplyLine(std::string_view line, const CodecParams& params) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  const std::vector<std::string_view> fields = splitAtCommas(line);
  if (fields.size() < 2) malformed(line, "no status");
  Reply reply;
  reply.command = replyCommand(line, fields[0]);
  const std::optional<int64_t> code = parseNumber<int64_t>(fields[1]);
  const std::optional<Status> status = code ? statusFromCode(*code) : std::nullopt;
  if (!status) malformed(line, "the status is no status code");
  reply.status = *status;
  const std::size_t numbers = fields.size() - 2;
  const std::size_t poseValues =
      3 + static_cast<std::size_t>(orientationValueCount(params.orientation));
  const bool hasPose = numbers > kMaxReplyIntegers;
  if (hasPose && (numbers < poseValues || numbers - poseValues > kMaxReplyIntegers)) {
    malformed(line, "neither up to 3 integers nor up to 3 integers and a pose");
  }
  const std::size_t integers = hasPose ? numbers - poseValues : numbers;
  for (std::size_t i = 0; i < integers; ++i) {
    const std::optional<int32_t> integer = parseNumber<int32_t>(fields[2 + i]);
    if (!integer) malformed(line, "an integer field is no int32");
    reply.integers.push_back(*integer);
  }
  if (hasPose) {
    reply.T_base_tool =
        parsePose(line, {fields.begin() + 2 + static_cast<std::ptrdiff_t>(integers), fields.end()},
                  params.orientation);
  }
  try {
    checkReply(reply);
  } catch (const Error& error) {
    malformed(line, error.what());
  }
  return reply;
}

}  // namespace binpick::robot::detail
