#pragma once
// The robot protocol's messages and their two wire framings (docs/robot-protocol.md).
//
// The robot controller is the TCP client; every request gets exactly one reply. ASCII framing:
// "CMD[,arg]\r\n" in, "CMD,status[,integers...][,x,y,z,orientation...]\r\n" out, every reply at
// most 80 characters (ABB's string limit) and at most 30 numbers (UR's socket_read_ascii_float).
// Binary framing: fixed-size messages of int32 fields in a selectable byte order (big-endian for
// FANUC), positions and orientation values in fixed point; a request's size follows from its
// command id (POSE carries a pose, every other request an argument).
//
// Poses cross the wire in millimetres with the orientation in one of the robot brands'
// conventions (robot_orientation.hpp); inside they are Eigen::Isometry3d in metres.
//
// Decoders and encoders hold no shared state: one per connection, used by one thread.
#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "binpick/core/orientation.hpp"

namespace binpick::robot {

// Wire values are fixed: never renumber.
enum class Command : int32_t {
  Ping = 1,         // PING: is the service there?
  Status = 2,       // STATUS: state, selected model, cycles done
  Trigger = 3,      // TRIGGER[,model]: start a cycle; the reply comes once the capture is done
  NextPick = 4,     // NEXT: the next pick of the latest cycle (waits for the cycle's result)
  PickFailed = 5,   // FAILED[,object]: that object (default: the last one handed out) is avoided
  SelectModel = 6,  // MODEL,name|index: the recipe for the next cycles
  Pose = 7,         // POSE,x,y,z,v1,v2,v3[,v4]: the robot's flange pose, for a hand-eye view
  // Replies only: the answer to a line in which no command could be read ("ERROR,8"), so that a
  // robot matching replies to its requests never reads one it did not send. No request has it;
  // the binary framing never needs it (every message starts with an id, which is echoed).
  Unreadable = -1,
};

// Wire values are fixed: never renumber.
enum class Status : int32_t {
  Ok = 0,                  // done; for NEXT: an object found, its pick in the reply
  NoObjects = 1,           // the bin holds something but no part was detected
  BinEmpty = 2,            // the bin holds nothing
  NoImage = 3,             // no capture: camera or projector fault
  CalibrationMissing = 4,  // no usable calibration (camera rig or hand-eye)
  Busy = 5,                // a cycle is already running
  Timeout = 6,             // a stage missed its deadline
  UnknownCommand = 7,
  BadMessage = 8,      // malformed, truncated, oversized or a bad argument
  NoCycle = 9,         // NEXT / FAILED before any cycle ran
  NoMorePicks = 10,    // every pick of the latest cycle was handed out
  UnknownModel = 11,   // MODEL / TRIGGER named no configured model
  Unreachable = 12,    // parts detected, but every grasp collides or is avoided
  InternalError = 13,  // the cycle failed for another reason (logged)
  BoardNotFound = 14,  // POSE: the image holds no usable calibration board
};

// A Command outside the enumerators stands for an unknown command (see Decoded): "UNKNOWN".
const char* commandKeyword(Command command);  // "PING", "STATUS", ..., "ERROR", "UNKNOWN"
const char* statusName(Status status);        // "ok", "no_objects", ...; "unknown" if none
bool isKnownCommand(Command command);         // a request's command: an enumerator but Unreadable

// Arguments: TRIGGER and MODEL take a model name or index, FAILED an object id (decimal, at most
// 2147483647, stored without leading zeros), PING, STATUS, NEXT and POSE none; MODEL requires
// one. An argument is 1..32 visible ASCII characters (0x21..0x7e) other than ','. The binary
// framing carries a non-negative int32 (its decimal text here) and ignores it for commands taking
// none. POSE, and only POSE, carries a pose: where the robot's flange is in its base frame, as
// the pendant shows it (x, y, z in millimetres on the wire, then the orientation values of the
// codec's convention: 3, or 4 for quaternions).
struct Request {
  Command command = Command::Ping;
  // The {} initialisers let Request{command, argument} compile clean under -Wextra.
  std::optional<std::string> argument{};             // binary framing: the int32 in decimal
  std::optional<Eigen::Isometry3d> T_base_flange{};  // POSE: the flange pose, metres
};

// Up to three integers follow the status; their meaning depends on the command:
//   STATUS: state (0 idle, 1 capturing, 2 computing), selected model index, cycles done
//   TRIGGER: cycle number;  MODEL: selected model index
//   NEXT: picks remaining after this one, object id, grasp id
//   POSE: views accepted so far, views wanted
struct Reply {
  Command command = Command::Ping;
  Status status = Status::Ok;
  // The {} initialisers let Reply{command, status} compile clean under -Wextra.
  std::vector<int32_t> integers{};                 // at most kMaxReplyIntegers
  std::optional<Eigen::Isometry3d> T_base_tool{};  // NEXT with status ok: the pick, metres
};
constexpr std::size_t kMaxReplyIntegers = 3;

enum class Framing { Ascii, Binary };
enum class ByteOrder { Little, Big };
// "ascii" | "binary" and "big" | "little"; throw core::Error listing the names otherwise.
Framing framingFromName(const std::string& name);
ByteOrder byteOrderFromName(const std::string& name);

// validate(): max_line_length in [16, 4096], decimals in [0, 9], scales finite and > 0.
// With the ASCII defaults a pose reads back within 0.01 mm and 0.001 degrees; with the binary
// defaults (1e-4 orientation units) within 0.01 mm and 0.01 degrees.
struct CodecParams {
  Framing framing = Framing::Ascii;
  core::Orientation orientation = core::Orientation::Quaternion;
  // ASCII: the longest line accepted or sent, terminator included (ABB reads 80 characters).
  std::size_t max_line_length = 80;
  int position_decimals = 2;     // ASCII: millimetres
  int orientation_decimals = 5;  // ASCII: quaternion components, radians or degrees
  // Binary: int32 field = round(value * scale).
  ByteOrder byte_order = ByteOrder::Big;
  double position_scale = 100.0;       // per millimetre (0.01 mm resolution)
  double orientation_scale = 10000.0;  // per orientation unit
  // Throws core::Error naming owner.FIELD; the owner is where the settings were read from.
  void validate(const std::string& owner = "robot_protocol") const;
};

// Binary sizes: a request is {command, argument}, except POSE's {command, x, y, z, 4 orientation
// values (unused ones 0)}; a reply is {command, status, 3 integers, x, y, z, 4 orientation
// values (unused ones 0)}, all int32.
constexpr std::size_t kBinaryRequestSize = 2 * 4;
constexpr std::size_t kBinaryPoseRequestSize = 8 * 4;
constexpr std::size_t kMaxBinaryRequestSize = kBinaryPoseRequestSize;
constexpr std::size_t kBinaryReplySize = 12 * 4;

// A decoded request, or why the bytes were not one. `command` is known for an error reply
// whenever the keyword or id could be read; else it is Unreadable with BadMessage ("ERROR,8").
// An ASCII keyword is read up to the first ',' or byte outside 0x20..0x7e: "NEXT\0" is a bad
// NEXT ("NEXT,8"), "\x01\x02", ",,," or "NE\0XT" unreadable; an oversized line's keyword counts
// only when such a byte or its comma came within max_line_length. For UnknownCommand it is no
// request's command: the raw id (binary) or 0 (ASCII), so that encodeReply(Reply{decoded.command,
// decoded.error}, params) echoes the id the robot sent (binary) or answers "UNKNOWN,7" (ASCII).
struct Decoded {
  std::optional<Request> request;
  Status error = Status::Ok;  // UnknownCommand or BadMessage when !request
  Command command = Command::Ping;
  std::string detail;       // what was wrong, for the log (printable ASCII only)
  int32_t raw_command = 0;  // binary framing: the command id as received; ASCII: 0
};

// Splits a byte stream into requests. ASCII: lines end with "\n" ("\r\n" accepted); a line
// longer than max_line_length (terminator included) is one BadMessage and is skipped up to its
// end; a line holding a byte below 0x20 (other than the terminator) or above 0x7e is BadMessage;
// keywords are case-insensitive, spaces around keyword and argument are trimmed, a blank line
// is ignored, an unknown keyword is UnknownCommand (one cut short by such a byte, or none at
// all, is Unreadable), a second argument or a bad one BadMessage.
// POSE needs exactly x, y, z and the convention's orientation values, each a finite decimal
// number (from_chars syntax: no '+', no "nan" or "inf"), else BadMessage; a zero quaternion is
// BadMessage too. Binary: the first int32 is the command id; POSE's id makes the request
// kBinaryPoseRequestSize bytes, any other id kBinaryRequestSize; an unknown id is
// UnknownCommand, a POSE whose unused orientation fields are not 0 (or whose quaternion is zero)
// BadMessage. However the stream is split into feed() calls, the same messages come out. Holds
// at most max_line_length bytes (ASCII) or kMaxBinaryRequestSize - 1 bytes (binary) of an
// incomplete message. Not thread-safe: one per connection.
class RequestDecoder {
 public:
  explicit RequestDecoder(const CodecParams& params);
  void feed(const char* data, std::size_t size);
  std::optional<Decoded> next();  // the next complete message, if any
  std::size_t buffered() const;   // bytes held for an incomplete message
 private:
  void feedAscii(const char* data, std::size_t size);
  void feedBinary(const char* data, std::size_t size);

  CodecParams params_;
  std::string buffer_;
  bool discarding_ = false;     // inside an oversized line
  std::vector<Decoded> ready_;  // decoded, not yet handed out: ready_[next_..]
  std::size_t next_ = 0;
};

// Never longer than max_line_length (ASCII) or kBinaryReplySize. ASCII numbers are fixed-point
// ("-0.00" written as "0.00"), integers plain. A quaternion goes onto the decimal (or int32)
// grid at the point whose rotation is closest, not component by component: that keeps the
// 5-decimal error below 0.001 degrees (rounding each component reaches 0.0011).
// With the defaults a reply fits 80 characters at full precision whenever x, y, z lie within
// +-10 m and the integers within 0..99. A longer reply first gives up precision, one decimal at
// a time, orientation first, at most one position decimal and two orientation decimals (the
// worst case, three integers of 99999 and a pose at 99 m, fits with 0.1 mm and 1e-3
// orientation units). A reply that still does not fit (or a binary value that overflows int32)
// is sent as "KEYWORD,8" / status BadMessage without integers and pose: never a truncated line.
// A pick (NEXT ok) goes out as NEXT's three integers and the pose; one with fewer integers
// cannot be sent as ASCII (a robot would read its x as the grasp id): "NEXT,8" too. The binary
// framing sends unused integers as 0.
// Throws core::Error on invalid params or a malformed reply: more than kMaxReplyIntegers
// integers, a pose other than on NEXT with status Ok (the binary framing could not tell it
// from none), a NEXT Ok without a pose, or a non-finite pose. Stateless: thread-safe.
std::string encodeReply(const Reply& reply, const CodecParams& params);
// encodeReply without the bad_message stand-in: nothing when the reply does not fit the framing
// (ASCII line too long at every allowed precision or a pick without its three integers, binary
// value beyond int32). For a sender that must know whether the robot would get what it was
// meant to (a pick handed out is used up).
std::optional<std::string> encodeReplyIfItFits(const Reply& reply, const CodecParams& params);

// The robot's side (binpick robot-client, tests): requests out, replies in. ASCII requests end
// with "\r\n"; a POSE is written at the codec's precision (position_decimals, orientation_decimals
// or the scales; with the defaults a pose within +-10 m fits 80 characters in every convention).
// Throws core::Error on an argument the request's command does not take (see Request), one the
// binary framing cannot carry (anything but a non-negative int32), a POSE without a finite pose
// or a pose on another command, a pose value that overflows int32 (binary), or an ASCII line
// longer than max_line_length. Stateless: thread-safe.
std::string encodeRequest(const Request& request, const CodecParams& params);

// The inverse of encodeReply: pose rebuilt with rotationFromValues; "ERROR" comes back as
// Unreadable, "UNKNOWN" and unknown binary ids as Decoded's non-enumerator commands (each only
// with UnknownCommand or BadMessage).
// Fields are read by the reply's command, never guessed from their count: a pick (NEXT ok) is
// NEXT's three integers, then x, y, z and exactly the configured convention's values. A pick
// sent in another convention throws naming both counts (ASCII: "NEXT carries 6 pose values
// after its 3 integers; the quaternion convention has 7: ..."); in binary framing, where the
// layout is the same for all, a set fourth orientation field in a 3-value convention, or a
// quaternion far from unit length (beyond its grid's 2 / orientation_scale), throws the same
// way. Other replies carry up to three integers as they come and no pose.
// The binary framing always yields three integers (unused ones 0). A blank ASCII line is
// skipped; a malformed message is consumed before the throw, so next() can go on with the
// following one. Not thread-safe: one per connection.
class ReplyDecoder {
 public:
  explicit ReplyDecoder(const CodecParams& params);
  void feed(const char* data, std::size_t size);
  // The next complete reply; throws core::Error naming what was malformed.
  std::optional<Reply> next();

 private:
  CodecParams params_;
  std::string buffer_;
  bool discarding_ = false;  // inside an oversized line
};

}  // namespace binpick::robot
