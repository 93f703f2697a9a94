// Keywords, status names and the codec parameters' checks.
#include <array>
#include <cctype>
#include <cmath>

#include "binpick/io/error.hpp"
#include "robot_codec.hpp"

namespace binpick::robot {

namespace {

constexpr std::array<Command, 7> kCommands = {
    Command::Ping,       Command::Status,      Command::Trigger, Command::NextPick,
    Command::PickFailed, Command::SelectModel, Command::Pose};

constexpr int32_t kLastStatusCode = static_cast<int32_t>(Status::BoardNotFound);

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::toupper(static_cast<unsigned char>(a[i])) !=
        std::toupper(static_cast<unsigned char>(b[i]))) {
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
  throw Error("unknown framing \"" + name + "\" (use ascii or binary)");
}

ByteOrder byteOrderFromName(const std::string& name) {
  if (name == "big") return ByteOrder::Big;
  if (name == "little") return ByteOrder::Little;
  throw Error("unknown byte order \"" + name + "\" (use big or little)");
}

void CodecParams::validate() const {
  const std::string owner = "robot_protocol";
  requireField(max_line_length >= 16 && max_line_length <= 4096, owner, "max_line_length",
               "in [16, 4096] characters", max_line_length);
  requireField(position_decimals >= 0 && position_decimals <= 9, owner, "position_decimals",
               "in [0, 9]", position_decimals);
  requireField(orientation_decimals >= 0 && orientation_decimals <= 9, owner,
               "orientation_decimals", "in [0, 9]", orientation_decimals);
  requireField(std::isfinite(position_scale) && position_scale > 0.0, owner, "position_scale",
               "finite and > 0 (int32 units per millimetre)", position_scale);
  requireField(std::isfinite(orientation_scale) && orientation_scale > 0.0, owner,
               "orientation_scale", "finite and > 0 (int32 units per orientation unit)",
               orientation_scale);
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
