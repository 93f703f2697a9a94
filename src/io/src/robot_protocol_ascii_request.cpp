// ASCII requests: "KEYWORD[,argument]" lines, and "POSE,x,y,z,v1,v2,v3[,v4]".
#include <vector>

#include "binpick/io/error.hpp"
#include "robot_codec.hpp"

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

Decoded failure(Status error, Command command, std::string detail) {
  Decoded decoded;
  decoded.error = error;
  decoded.command = command;
  decoded.detail = std::move(detail);
  return decoded;
}

// POSE's fields after the keyword: the pose, every value a finite number.
Decoded decodePoseFields(const std::vector<std::string_view>& fields, Orientation orientation) {
  std::vector<double> values;
  for (std::size_t i = 1; i < fields.size(); ++i) {
    const std::optional<double> value = parseFiniteNumber(fields[i]);
    if (!value) {
      return failure(Status::BadMessage, Command::Pose,
                     "POSE value " + std::to_string(i) + " '" + std::string(fields[i]) +
                         "' is no finite number");
    }
    values.push_back(*value);
  }
  std::string problem;
  std::optional<Eigen::Isometry3d> T_base_flange =
      poseFromWireValues(values, orientation, problem);
  if (!T_base_flange) return failure(Status::BadMessage, Command::Pose, "POSE: " + problem);
  Decoded decoded;
  decoded.command = Command::Pose;
  decoded.request = Request{Command::Pose, std::nullopt, T_base_flange};
  return decoded;
}

// The request of a line whose keyword is known and whose bytes are all allowed.
Decoded decodeFields(Command command, const std::vector<std::string_view>& fields,
                     const CodecParams& params) {
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
  for (std::size_t comma = line.find(','); comma != std::string_view::npos;
       comma = line.find(',', start)) {
    fields.push_back(line.substr(start, comma - start));
    start = comma + 1;
  }
  fields.push_back(line.substr(start));
  return fields;
}

std::optional<Decoded> decodeAsciiRequestLine(std::string_view line, const CodecParams& params) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  if (trimSpaces(line).empty()) return std::nullopt;
  std::vector<std::string_view> fields = splitAtCommas(line);
  for (std::string_view& field : fields) field = trimSpaces(field);
  const std::string_view keyword = fields.front();
  if (holdsForbiddenByte(keyword)) {
    return failure(Status::BadMessage, Command::Ping,
                   "a control character or non-ASCII byte in the keyword");
  }
  const std::optional<Command> command = commandFromKeyword(keyword);
  if (!command) {
    if (keyword.empty()) return failure(Status::BadMessage, Command::Ping, "no keyword");
    return failure(Status::UnknownCommand, kUnknownAsciiCommand,
                   "unknown command '" + std::string(keyword) + "'");
  }
  if (holdsForbiddenByte(line)) {
    return failure(Status::BadMessage, *command,
                   "a control character or non-ASCII byte in the line");
  }
  return decodeFields(*command, fields, params);
}

Decoded oversizedAsciiRequest(std::string_view start) {
  // The keyword is known only if its comma arrived within the limit; else it is garbage.
  Command command = Command::Ping;
  const std::size_t comma = start.find(',');
  if (comma != std::string_view::npos) {
    const std::string_view keyword = trimSpaces(start.substr(0, comma));
    if (!holdsForbiddenByte(keyword)) command = commandFromKeyword(keyword).value_or(command);
  }
  return failure(Status::BadMessage, command, "a line longer than max_line_length");
}

std::string encodeAsciiRequest(const Request& request, const CodecParams& params) {
  std::string line = commandKeyword(request.command);
  if (request.argument) line += "," + *request.argument;
  if (request.T_base_flange) {
    const std::optional<std::string> pose =
        asciiPoseText(*request.T_base_flange, params.orientation, params.position_decimals,
                      params.orientation_decimals);
    if (!pose) throw Error("Request.T_base_flange is too far out to be written as a POSE line");
    line += *pose;
  }
  return line + "\r\n";
}

}  // namespace binpick::robot::detail
