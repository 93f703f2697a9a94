// What each command accepts, shared by both framings' decoders and the encoders' checks, so that
// whatever a decoder accepts an encoder writes back unchanged, and the other way round.
#include <charconv>
#include <cmath>
#include <limits>

#include "binpick/io/error.hpp"
#include "robot_codec.hpp"

namespace binpick::robot::detail {

namespace {

std::string keywordOf(Command command) { return commandKeyword(command); }

}  // namespace

bool takesArgument(Command command) {
  return command == Command::Trigger || command == Command::PickFailed ||
         command == Command::SelectModel;
}

bool isVisibleArgumentCharacter(char c) { return c > ' ' && c < 0x7f && c != ','; }

std::optional<int32_t> parseNonNegativeInt32(std::string_view digits) {
  if (digits.empty()) return std::nullopt;
  for (char c : digits) {
    if (c < '0' || c > '9') return std::nullopt;  // from_chars alone would accept '-'
  }
  int32_t value = 0;
  const auto result = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (result.ec != std::errc() || result.ptr != digits.data() + digits.size()) return std::nullopt;
  return value;
}

std::string argumentProblem(Command command, const std::optional<std::string>& argument) {
  if (!argument) {
    return command == Command::SelectModel ? "MODEL needs a model name or index" : "";
  }
  if (!takesArgument(command)) return keywordOf(command) + " takes no argument";
  if (argument->empty() || argument->size() > kMaxArgumentLength) {
    return "the argument must be 1 to 32 characters long";
  }
  for (char c : *argument) {
    if (!isVisibleArgumentCharacter(c)) {
      return "the argument may hold only visible ASCII characters other than ','";
    }
  }
  if (command == Command::PickFailed && !parseNonNegativeInt32(*argument)) {
    return "FAILED takes an object id: an integer in [0, 2147483647]";
  }
  return "";
}

std::optional<std::string> canonicalArgument(Command command,
                                             const std::optional<std::string>& argument) {
  if (command != Command::PickFailed || !argument) return argument;
  return std::to_string(*parseNonNegativeInt32(*argument));
}

void checkRequest(const Request& request) {
  if (!isKnownCommand(request.command)) {
    throw Error("Request.command " + std::to_string(static_cast<int32_t>(request.command)) +
                " is no command");
  }
  const std::string problem = argumentProblem(request.command, request.argument);
  if (!problem.empty()) throw Error("Request.argument: " + problem);
  const bool pose = request.command == Command::Pose;
  if (pose != request.T_base_flange.has_value()) {
    throw Error(pose ? "Request.T_base_flange is missing: POSE carries the flange pose"
                     : "Request.T_base_flange must be empty unless POSE");
  }
  if (request.T_base_flange && !request.T_base_flange->matrix().allFinite()) {
    throw Error("Request.T_base_flange must be finite");
  }
}

void checkReply(const Reply& reply) {
  const auto status = static_cast<int32_t>(reply.status);
  if (!statusFromCode(status)) {
    throw Error("Reply.status " + std::to_string(status) + " is no status");
  }
  // An unknown command is echoed with UnknownCommand, or BadMessage when that reply did not fit.
  if (!isKnownCommand(reply.command) && reply.status != Status::UnknownCommand &&
      reply.status != Status::BadMessage) {
    throw Error("Reply.command " + std::to_string(static_cast<int32_t>(reply.command)) +
                " is no command (allowed only with status unknown_command or bad_message)");
  }
  if (reply.integers.size() > kMaxReplyIntegers) {
    throw Error("Reply.integers must be at most 3 numbers (got " +
                std::to_string(reply.integers.size()) + ")");
  }
  const bool pick = reply.command == Command::NextPick && reply.status == Status::Ok;
  if (pick != reply.T_base_tool.has_value()) {
    throw Error(pick ? "Reply.T_base_tool is missing: NEXT with status ok carries the pick"
                     : "Reply.T_base_tool must be empty unless NEXT with status ok");
  }
  if (reply.T_base_tool && !reply.T_base_tool->matrix().allFinite()) {
    throw Error("Reply.T_base_tool must be finite");
  }
}

}  // namespace binpick::robot::detail
