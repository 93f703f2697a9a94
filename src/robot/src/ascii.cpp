// ASCII framing: requests "KEYWORD[,argument]" and "POSE,x,y,z,v1,v2,v3[,v4]"; replies
// "KEYWORD,status[,integers...][,x,y,z,orientation...]\r\n".
#include <array>
#include <charconv>
#include <cmath>
#include <vector>

#include "binpick/core/error.hpp"
#include "codec.hpp"

namespace binpick::robot::detail {

namespace {

// Below 0x20 or above 0x7e: NUL, tabs, stray carriage returns, UTF-8. Refused rather than
// skipped, so that a robot program writing garbage hears about it.
bool isForbiddenByte(char c) {
  const auto byte = static_cast<unsigned char>(c);
  return byte < 0x20 || byte > 0x7e;
}

bool holdsForbiddenByte(std::string_view text) {
  for (char c : text) {
    if (isForbiddenByte(c)) return true;
  }
  return false;
}

std::string_view trimSpaces(std::string_view text) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  return text;
}

// A line's keyword: its text up to the first comma or forbidden byte, spaces trimmed.
struct KeywordRead {
  std::string_view text;
  bool ended = false;      // a comma or a forbidden byte came after it
  bool cut_short = false;  // ... and it was a forbidden byte
};

KeywordRead readKeyword(std::string_view line) {
  KeywordRead keyword;
  std::size_t end = 0;
  while (end < line.size() && line[end] != ',' && !isForbiddenByte(line[end])) ++end;
  keyword.text = trimSpaces(line.substr(0, end));
  keyword.ended = end < line.size();
  keyword.cut_short = keyword.ended && line[end] != ',';
  return keyword;
}

Decoded failure(Status error, Command command, std::string detail) {
  Decoded decoded;
  decoded.error = error;
  decoded.command = command;
  decoded.detail = std::move(detail);
  return decoded;
}

// POSE's fields after the keyword: the pose, every value a finite number.
Decoded decodePoseFields(const std::vector<std::string_view>& fields, core::Orientation orientation) {
  std::vector<double> values;
  for (std::size_t i = 1; i < fields.size(); ++i) {
    const std::optional<double> value = parseFiniteNumber(fields[i]);
    if (!value) {
      return failure(Status::BadMessage, Command::Pose,
                     "POSE value " + std::to_string(i) + " '" + std::string(fields[i]) + "' is no finite number");
    }
    values.push_back(*value);
  }
  std::string problem;
  std::optional<Eigen::Isometry3d> T_base_flange = poseFromWireValues(values, orientation, problem);
  if (!T_base_flange) return failure(Status::BadMessage, Command::Pose, "POSE: " + problem);
  Decoded decoded;
  decoded.command = Command::Pose;
  decoded.request = Request{Command::Pose, std::nullopt, T_base_flange};
  return decoded;
}

// The request of a line whose keyword is known and whose bytes are all allowed.
Decoded decodeFields(Command command, const std::vector<std::string_view>& fields, const CodecParams& params) {
  if (command == Command::Pose) return decodePoseFields(fields, params.orientation);
  const std::string keyword = commandKeyword(command);
  if (fields.size() > 2) {
    return failure(Status::BadMessage, command, keyword + " takes at most one argument");
  }
  std::optional<std::string> argument;
  if (fields.size() == 2) argument = std::string(fields[1]);
  const std::string problem = argumentProblem(command, argument);
  if (!problem.empty()) return failure(Status::BadMessage, command, problem);
  Decoded decoded;
  decoded.command = command;
  decoded.request = Request{command, canonicalArgument(command, argument)};
  return decoded;
}

}  // namespace

std::vector<std::string_view> splitAtCommas(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  for (std::size_t comma = line.find(','); comma != std::string_view::npos; comma = line.find(',', start)) {
    fields.push_back(line.substr(start, comma - start));
    start = comma + 1;
  }
  fields.push_back(line.substr(start));
  return fields;
}

std::optional<Decoded> decodeAsciiRequestLine(std::string_view line, const CodecParams& params) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  if (trimSpaces(line).empty()) return std::nullopt;
  const KeywordRead keyword = readKeyword(line);
  const std::optional<Command> command = commandFromKeyword(keyword.text);
  if (keyword.cut_short) {
    // "NEXT\0" was a NEXT; "PI\0NG" or "\xff" names nothing: its reply must not name a command.
    return failure(Status::BadMessage, command.value_or(Command::Unreadable),
                   "a control character or non-ASCII byte in the keyword");
  }
  if (!command) {
    if (keyword.text.empty()) return failure(Status::BadMessage, Command::Unreadable, "no keyword");
    return failure(Status::UnknownCommand, kUnknownAsciiCommand, "unknown command '" + std::string(keyword.text) + "'");
  }
  if (holdsForbiddenByte(line)) {
    return failure(Status::BadMessage, *command, "a control character or non-ASCII byte in the line");
  }
  std::vector<std::string_view> fields = splitAtCommas(line);
  for (std::string_view& field : fields) field = trimSpaces(field);
  return decodeFields(*command, fields, params);
}

Decoded oversizedAsciiRequest(std::string_view start) {
  // The keyword is known only if its end (a comma or a forbidden byte) arrived within the limit.
  const KeywordRead keyword = readKeyword(start);
  const std::optional<Command> command = keyword.ended ? commandFromKeyword(keyword.text) : std::optional<Command>();
  return failure(Status::BadMessage, command.value_or(Command::Unreadable), "a line longer than max_line_length");
}

std::string encodeAsciiRequest(const Request& request, const CodecParams& params) {
  std::string line = commandKeyword(request.command);
  if (request.argument) line += "," + *request.argument;
  if (request.T_base_flange) {
    const std::optional<std::string> pose = asciiPoseText(*request.T_base_flange, params.orientation,
                                                          params.position_decimals, params.orientation_decimals);
    if (!pose) throw core::Error("Request.T_base_flange is too far out to be written as a POSE line");
    line += *pose;
  }
  return line + "\r\n";
}

namespace {

// NEXT's integers: picks remaining, object id, grasp id (docs/robot-protocol.md, "Reply shapes").
// A robot finds the pick's pose after them, so a pick always has all three.
constexpr std::size_t kPickIntegers = 3;

bool carriesPick(const Reply& reply) { return reply.command == Command::NextPick && reply.status == Status::Ok; }

// How many decimals a reply gives up, in turn, when it is too long at full precision: the
// orientation first (a quaternion's fifth decimal moves a point 200 mm from the flange by
// ~2 um, a position's second decimal by 10 um), and never more than these.
struct PrecisionDrop {
  int position, orientation;
};
constexpr std::array<PrecisionDrop, 4> kPrecisionDrops = {{{0, 0}, {0, 1}, {1, 1}, {1, 2}}};

std::optional<std::string> poseText(const Eigen::Isometry3d& T_base_tool, const CodecParams& params,
                                    PrecisionDrop drop) {
  return asciiPoseText(T_base_tool, params.orientation, std::max(0, params.position_decimals - drop.position),
                       std::max(0, params.orientation_decimals - drop.orientation));
}

// --- decoding

[[noreturn]] void malformed(std::string_view line, const std::string& problem) {
  std::string shown(line.substr(0, 100));
  for (char& c : shown) {
    if (c < 0x20 || c > 0x7e) c = '?';  // the message goes to logs and terminals
  }
  throw core::Error("malformed reply '" + shown + "': " + problem);
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
  if (keyword == kUnreadableKeyword) return Command::Unreadable;
  malformed(line, "unknown keyword");
}

Eigen::Isometry3d parsePose(std::string_view line, const std::vector<std::string_view>& fields,
                            core::Orientation orientation) {
  std::vector<double> values;
  for (std::string_view field : fields) {
    const std::optional<double> value = parseFiniteNumber(field);
    if (!value) malformed(line, "a pose value is no finite number");
    values.push_back(*value);
  }
  std::string problem;
  const std::optional<Eigen::Isometry3d> T_base_tool = poseFromWireValues(values, orientation, problem);
  if (!T_base_tool) malformed(line, problem);
  return *T_base_tool;
}

std::vector<int32_t> parseIntegers(std::string_view line, const std::vector<std::string_view>& fields) {
  std::vector<int32_t> integers;
  for (std::string_view field : fields) {
    const std::optional<int32_t> integer = parseNumber<int32_t>(field);
    if (!integer) malformed(line, "an integer field is no int32");
    integers.push_back(*integer);
  }
  return integers;
}

// A pick is NEXT's three integers, then x, y, z and the convention's values. The integers are
// counted by the command, never from the line's length: a pick sent in a 3-value convention and
// read in the 4-value one (or the other way round) would otherwise come out with every field
// shifted by one, the grasp id read as x.
void readPick(std::string_view line, const std::vector<std::string_view>& numbers, core::Orientation orientation,
              Reply& reply) {
  if (numbers.size() < kPickIntegers) {
    malformed(line, "NEXT ok carries 3 integers (picks remaining, object id, grasp id) and the pose (got " +
                        std::to_string(numbers.size()) + " numbers)");
  }
  const std::size_t poseValues = numbers.size() - kPickIntegers;
  const std::size_t expected = 3 + static_cast<std::size_t>(core::orientationValueCount(orientation));
  if (poseValues != expected) {
    malformed(line, "NEXT carries " + std::to_string(poseValues) + " pose values after its 3 integers; the " +
                        core::orientationName(orientation) + " convention has " + std::to_string(expected) +
                        ": is --orientation the cell's robot.orientation?");
  }
  const auto poseStart = numbers.begin() + static_cast<std::ptrdiff_t>(kPickIntegers);
  reply.integers = parseIntegers(line, {numbers.begin(), poseStart});
  reply.T_base_tool = parsePose(line, {poseStart, numbers.end()}, orientation);
}

}  // namespace

std::optional<std::string> encodeAsciiReply(const Reply& reply, const CodecParams& params) {
  // A pick with fewer integers would put its x where a robot (and ReplyDecoder) reads the grasp
  // id: the line cannot carry it, as one too long cannot.
  if (reply.T_base_tool && reply.integers.size() != kPickIntegers) return std::nullopt;
  std::string head =
      std::string(commandKeyword(reply.command)) + "," + std::to_string(static_cast<int32_t>(reply.status));
  for (int32_t integer : reply.integers) head += "," + std::to_string(integer);
  if (!reply.T_base_tool) {
    std::string line = head + "\r\n";
    if (line.size() > params.max_line_length) return std::nullopt;
    return line;
  }
  for (const PrecisionDrop& drop : kPrecisionDrops) {
    const std::optional<std::string> pose = poseText(*reply.T_base_tool, params, drop);
    if (!pose) break;
    const std::string line = head + *pose + "\r\n";
    if (line.size() <= params.max_line_length) return line;
  }
  return std::nullopt;
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
  const std::vector<std::string_view> numbers(fields.begin() + 2, fields.end());
  if (carriesPick(reply)) {
    readPick(line, numbers, params.orientation, reply);
  } else {
    if (numbers.size() > kMaxReplyIntegers) {
      malformed(line, std::string(commandKeyword(reply.command)) + " " + statusName(reply.status) +
                          " carries at most 3 integers and no pose (got " + std::to_string(numbers.size()) +
                          " numbers)");
    }
    reply.integers = parseIntegers(line, numbers);
  }
  try {
    checkReply(reply);
  } catch (const core::Error& error) {
    malformed(line, error.what());
  }
  return reply;
}

}  // namespace binpick::robot::detail
