// The protocol apart from its framings: keywords, status names and the codec parameters' checks;
// what each command accepts (shared by both framings' decoders and the encoders' checks, so that
// whatever a decoder accepts an encoder writes back unchanged); and the stream side, which splits
// bytes into messages.
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>

#include "binpick/core/error.hpp"
#include "codec.hpp"

namespace binpick::robot {

namespace {

constexpr std::array<Command, 7> kCommands = {Command::Ping,     Command::Status,     Command::Trigger,
                                              Command::NextPick, Command::PickFailed, Command::SelectModel,
                                              Command::Pose};

constexpr int32_t kLastStatusCode = static_cast<int32_t>(Status::BoardNotFound);

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::toupper(static_cast<unsigned char>(a[i])) != std::toupper(static_cast<unsigned char>(b[i]))) {
      return false;
    }
  }
  return true;
}

}  // namespace

const char* commandKeyword(Command command) {
  switch (command) {
    case Command::Ping: return "PING";
    case Command::Status: return "STATUS";
    case Command::Trigger: return "TRIGGER";
    case Command::NextPick: return "NEXT";
    case Command::PickFailed: return "FAILED";
    case Command::SelectModel: return "MODEL";
    case Command::Pose: return "POSE";
    case Command::Unreadable: return detail::kUnreadableKeyword;
  }
  return detail::kUnknownKeyword;
}

bool isKnownCommand(Command command) {
  for (Command known : kCommands) {
    if (known == command) return true;
  }
  return false;
}

const char* statusName(Status status) {
  switch (status) {
    case Status::Ok: return "ok";
    case Status::NoObjects: return "no_objects";
    case Status::BinEmpty: return "bin_empty";
    case Status::NoImage: return "no_image";
    case Status::CalibrationMissing: return "calibration_missing";
    case Status::Busy: return "busy";
    case Status::Timeout: return "timeout";
    case Status::UnknownCommand: return "unknown_command";
    case Status::BadMessage: return "bad_message";
    case Status::NoCycle: return "no_cycle";
    case Status::NoMorePicks: return "no_more_picks";
    case Status::UnknownModel: return "unknown_model";
    case Status::Unreachable: return "unreachable";
    case Status::InternalError: return "internal_error";
    case Status::BoardNotFound: return "board_not_found";
  }
  return "unknown";
}

Framing framingFromName(const std::string& name) {
  if (name == "ascii") return Framing::Ascii;
  if (name == "binary") return Framing::Binary;
  throw core::Error("unknown framing \"" + name + "\" (use ascii or binary)");
}

ByteOrder byteOrderFromName(const std::string& name) {
  if (name == "big") return ByteOrder::Big;
  if (name == "little") return ByteOrder::Little;
  throw core::Error("unknown byte order \"" + name + "\" (use big or little)");
}

void CodecParams::validate(const std::string& owner) const {
  core::requireField(max_line_length >= 16 && max_line_length <= 4096, owner, "max_line_length",
                     "in [16, 4096] characters", max_line_length);
  core::requireField(position_decimals >= 0 && position_decimals <= 9, owner, "position_decimals", "in [0, 9]",
                     position_decimals);
  core::requireField(orientation_decimals >= 0 && orientation_decimals <= 9, owner, "orientation_decimals", "in [0, 9]",
                     orientation_decimals);
  core::requireField(std::isfinite(position_scale) && position_scale > 0.0, owner, "position_scale",
                     "finite and > 0 (int32 units per millimetre)", position_scale);
  core::requireField(std::isfinite(orientation_scale) && orientation_scale > 0.0, owner, "orientation_scale",
                     "finite and > 0 (int32 units per orientation unit)", orientation_scale);
}

namespace detail {

std::optional<Command> commandFromKeyword(std::string_view keyword) {
  for (Command command : kCommands) {
    if (equalsIgnoringCase(keyword, commandKeyword(command))) return command;
  }
  return std::nullopt;
}

std::optional<Status> statusFromCode(int64_t code) {
  if (code < 0 || code > kLastStatusCode) return std::nullopt;
  return static_cast<Status>(code);
}

}  // namespace detail

}  // namespace binpick::robot

namespace binpick::robot::detail {

namespace {

std::string keywordOf(Command command) { return commandKeyword(command); }

}  // namespace

bool takesArgument(Command command) {
  return command == Command::Trigger || command == Command::PickFailed || command == Command::SelectModel;
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

std::optional<std::string> canonicalArgument(Command command, const std::optional<std::string>& argument) {
  if (command != Command::PickFailed || !argument) return argument;
  return std::to_string(*parseNonNegativeInt32(*argument));
}

void checkRequest(const Request& request) {
  if (!isKnownCommand(request.command)) {
    throw core::Error("Request.command " + std::to_string(static_cast<int32_t>(request.command)) + " is no command");
  }
  const std::string problem = argumentProblem(request.command, request.argument);
  if (!problem.empty()) throw core::Error("Request.argument: " + problem);
  const bool pose = request.command == Command::Pose;
  if (pose != request.T_base_flange.has_value()) {
    throw core::Error(pose ? "Request.T_base_flange is missing: POSE carries the flange pose"
                           : "Request.T_base_flange must be empty unless POSE");
  }
  if (request.T_base_flange && !request.T_base_flange->matrix().allFinite()) {
    throw core::Error("Request.T_base_flange must be finite");
  }
}

void checkReply(const Reply& reply) {
  const auto status = static_cast<int32_t>(reply.status);
  if (!statusFromCode(status)) {
    throw core::Error("Reply.status " + std::to_string(status) + " is no status");
  }
  // An unknown command is echoed with UnknownCommand, or BadMessage when that reply did not fit.
  if (!isKnownCommand(reply.command) && reply.status != Status::UnknownCommand && reply.status != Status::BadMessage) {
    throw core::Error("Reply.command " + std::to_string(static_cast<int32_t>(reply.command)) +
                      " is no command (allowed only with status unknown_command or bad_message)");
  }
  if (reply.integers.size() > kMaxReplyIntegers) {
    throw core::Error("Reply.integers must be at most 3 numbers (got " + std::to_string(reply.integers.size()) + ")");
  }
  const bool pick = reply.command == Command::NextPick && reply.status == Status::Ok;
  if (pick != reply.T_base_tool.has_value()) {
    throw core::Error(pick ? "Reply.T_base_tool is missing: NEXT with status ok carries the pick"
                           : "Reply.T_base_tool must be empty unless NEXT with status ok");
  }
  if (reply.T_base_tool && !reply.T_base_tool->matrix().allFinite()) {
    throw core::Error("Reply.T_base_tool must be finite");
  }
}

}  // namespace binpick::robot::detail

namespace binpick::robot {

namespace {

// The bytes of [data, data + size) up to the next '\n', or nothing if none is there.
std::optional<std::size_t> newlineOffset(const char* data, std::size_t size) {
  for (std::size_t i = 0; i < size; ++i) {
    if (data[i] == '\n') return i;
  }
  return std::nullopt;
}

}  // namespace

RequestDecoder::RequestDecoder(const CodecParams& params) : params_(params) { params_.validate(); }

void RequestDecoder::feed(const char* data, std::size_t size) {
  if (params_.framing == Framing::Binary) {
    feedBinary(data, size);
  } else {
    feedAscii(data, size);
  }
}

void RequestDecoder::feedBinary(const char* data, std::size_t size) {
  buffer_.append(data, size);
  std::size_t start = 0;
  // The command id tells how long its request is; until it has arrived, nothing is decided.
  constexpr std::size_t kIdSize = 4;
  while (buffer_.size() - start >= kIdSize) {
    const std::size_t length = detail::binaryRequestSize(detail::readInt32(buffer_.data() + start, params_.byte_order));
    if (buffer_.size() - start < length) break;
    ready_.push_back(detail::decodeBinaryRequest(buffer_.data() + start, params_));
    start += length;
  }
  buffer_.erase(0, start);
}

void RequestDecoder::feedAscii(const char* data, std::size_t size) {
  // A line of n bytes before its '\n' is n + 1 long: too long once n >= max_line_length,
  // which is decided the same way whether its '\n' is in sight yet or not.
  const std::size_t limit = params_.max_line_length;
  while (size > 0) {
    const std::optional<std::size_t> newline = newlineOffset(data, size);
    if (discarding_) {
      if (!newline) return;
      discarding_ = false;
    } else if (newline && buffer_.size() + *newline < limit) {
      buffer_.append(data, *newline);
      if (auto decoded = detail::decodeAsciiRequestLine(buffer_, params_)) {
        ready_.push_back(std::move(*decoded));
      }
      buffer_.clear();
    } else if (buffer_.size() + (newline ? *newline : size) >= limit) {
      buffer_.append(data, std::min(size, limit - buffer_.size()));
      ready_.push_back(detail::oversizedAsciiRequest(buffer_.substr(0, limit)));
      buffer_.clear();
      discarding_ = !newline;
      if (!newline) return;
    } else {
      buffer_.append(data, size);  // an incomplete line, shorter than the limit so far
      return;
    }
    data += *newline + 1;
    size -= *newline + 1;
  }
}

std::optional<Decoded> RequestDecoder::next() {
  if (next_ == ready_.size()) return std::nullopt;
  Decoded decoded = std::move(ready_[next_++]);
  if (next_ == ready_.size()) {  // all handed out: reuse the storage
    ready_.clear();
    next_ = 0;
  }
  return decoded;
}

std::size_t RequestDecoder::buffered() const { return buffer_.size(); }

std::optional<std::string> encodeReplyIfItFits(const Reply& reply, const CodecParams& params) {
  params.validate();
  detail::checkReply(reply);
  return params.framing == Framing::Ascii ? detail::encodeAsciiReply(reply, params)
                                          : detail::encodeBinaryReply(reply, params);
}

std::string encodeReply(const Reply& reply, const CodecParams& params) {
  if (std::optional<std::string> bytes = encodeReplyIfItFits(reply, params)) return std::move(*bytes);
  // No integers and no pose: "KEYWORD,8" fits every line limit, and a binary reply without a pose
  // cannot overflow.
  Reply bad_message;
  bad_message.command = reply.command;
  bad_message.status = Status::BadMessage;
  return *encodeReplyIfItFits(bad_message, params);
}

std::string encodeRequest(const Request& request, const CodecParams& params) {
  params.validate();
  detail::checkRequest(request);
  if (params.framing == Framing::Binary) return detail::encodeBinaryRequest(request, params);
  std::string line = detail::encodeAsciiRequest(request, params);
  if (line.size() > params.max_line_length) {
    throw core::Error("Request: '" + line.substr(0, line.size() - 2) + "' is longer than " +
                      std::to_string(params.max_line_length) + " characters (max_line_length)");
  }
  return line;
}

ReplyDecoder::ReplyDecoder(const CodecParams& params) : params_(params) { params_.validate(); }

void ReplyDecoder::feed(const char* data, std::size_t size) { buffer_.append(data, size); }

std::optional<Reply> ReplyDecoder::next() {
  if (params_.framing == Framing::Binary) {
    if (buffer_.size() < kBinaryReplySize) return std::nullopt;
    const std::string message = buffer_.substr(0, kBinaryReplySize);
    buffer_.erase(0, kBinaryReplySize);  // consumed before a throw: next() goes on after it
    return detail::decodeBinaryReply(message.data(), params_);
  }
  while (true) {
    const std::size_t newline = buffer_.find('\n');
    if (discarding_) {
      if (newline == std::string::npos) {
        buffer_.clear();
        return std::nullopt;
      }
      buffer_.erase(0, newline + 1);
      discarding_ = false;
      continue;
    }
    const std::size_t length = newline == std::string::npos ? buffer_.size() : newline;
    if (length >= params_.max_line_length) {
      discarding_ = newline == std::string::npos;
      buffer_.erase(0, newline == std::string::npos ? buffer_.size() : newline + 1);
      throw core::Error("malformed reply: a line longer than " + std::to_string(params_.max_line_length) +
                        " characters (max_line_length)");
    }
    if (newline == std::string::npos) return std::nullopt;
    const std::string line = buffer_.substr(0, newline);
    buffer_.erase(0, newline + 1);
    if (line.empty() || line == "\r") continue;
    return detail::decodeAsciiReplyLine(line, params_);
  }
}

}  // namespace binpick::robot
