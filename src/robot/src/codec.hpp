#pragma once
// Internal: the pieces RequestDecoder, ReplyDecoder, encodeReply and encodeRequest are made of.
// Each framing's codec works on one complete message; the stream classes do the splitting.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "binpick/robot/protocol.hpp"

namespace binpick::robot::detail {

constexpr std::size_t kMaxArgumentLength = 32;
constexpr double kMillimetresPerMetre = 1000.0;  // poses cross the wire in millimetres
// Decoded::command / Reply::command for an unknown ASCII keyword (no enumerator is 0).
constexpr Command kUnknownAsciiCommand = static_cast<Command>(0);
constexpr const char* kUnknownKeyword = "UNKNOWN";
constexpr const char* kUnreadableKeyword = "ERROR";  // Command::Unreadable

// --- names and arguments (protocol.cpp)
std::optional<Command> commandFromKeyword(std::string_view keyword);  // case-insensitive
std::optional<Status> statusFromCode(int64_t code);
bool takesArgument(Command command);  // TRIGGER, FAILED, MODEL
// Why `argument` does not suit `command` (see Request), or "" when it does.
std::string argumentProblem(Command command, const std::optional<std::string>& argument);
// FAILED's object id without leading zeros; other arguments unchanged. Call after the check.
std::optional<std::string> canonicalArgument(Command command, const std::optional<std::string>& argument);
// A non-negative int32 written as plain decimal digits, or nothing.
std::optional<int32_t> parseNonNegativeInt32(std::string_view digits);
bool isVisibleArgumentCharacter(char c);
// Throws core::Error naming the first problem of a request or reply an encoder was handed.
void checkRequest(const Request& request);
void checkReply(const Reply& reply);

// --- poses in either framing (pose.cpp)
// x, y, z in millimetres, then the orientation values of `orientation`: the pose, or nothing with
// `problem` saying why (a wrong count, a zero quaternion). Positions are taken as they are.
std::optional<Eigen::Isometry3d> poseFromWireValues(const std::vector<double>& values, core::Orientation orientation,
                                                    std::string& problem);
// A whole field as a finite number (from_chars syntax), or nothing.
std::optional<double> parseFiniteNumber(std::string_view text);
// ",x,y,z,o1,o2,o3[,o4]" at the given decimals; nothing when a value is too large to print.
std::optional<std::string> asciiPoseText(const Eigen::Isometry3d& T, core::Orientation orientation,
                                         int positionDecimals, int orientationDecimals);
// The binary pose fields {x, y, z, o1..o4} (unused orientation fields 0), nothing on overflow.
constexpr std::size_t kBinaryPoseFields = 7;
using BinaryPoseFields = std::array<int32_t, kBinaryPoseFields>;
std::optional<BinaryPoseFields> binaryPoseFields(const Eigen::Isometry3d& T, const CodecParams& params);
// The inverse; nothing with `problem` saying why (an unused field not 0, a zero quaternion).
std::optional<Eigen::Isometry3d> poseFromBinaryFields(const BinaryPoseFields& fields, const CodecParams& params,
                                                      std::string& problem);

// --- quaternion rounding (pose.cpp)
// The quaternion w, x, y, z (unit, w >= 0) in whole units of 1 / unitsPerValue: of the 16 ways
// to round each value down or up, the one whose rotation is closest to q's. Rounding each to the
// nearest leaves up to 0.0011 degrees at 5 decimals; the best corner stayed below 0.00093 over
// two million random rotations, within the 0.001 degrees the ASCII defaults promise.
std::array<double, 4> roundQuaternion(const std::vector<double>& q, double unitsPerValue);

// --- ASCII framing (ascii.cpp)
std::vector<std::string_view> splitAtCommas(std::string_view line);  // fields as they are
// `line` is one line without its '\n' (a trailing '\r' is allowed); nothing for a blank line.
std::optional<Decoded> decodeAsciiRequestLine(std::string_view line, const CodecParams& params);
// The BadMessage for a line longer than the limit; `start` is its first max_line_length bytes.
Decoded oversizedAsciiRequest(std::string_view start);
std::string encodeAsciiRequest(const Request& request, const CodecParams& params);
// Nothing when the line exceeds max_line_length even at the lowest precision allowed.
std::optional<std::string> encodeAsciiReply(const Reply& reply, const CodecParams& params);
// `line` without its '\n'; throws core::Error naming what was malformed.
Reply decodeAsciiReplyLine(std::string_view line, const CodecParams& params);

// --- binary framing (binary.cpp)
// Byte by byte through uint32_t: the same on any host byte order.
void appendInt32(std::string& out, int32_t value, ByteOrder order);
int32_t readInt32(const char* bytes, ByteOrder order);
// round(value * scale), nothing when that does not fit an int32.
std::optional<int32_t> fixedPoint(double value, double scale);
// The size of a request whose first int32 is `id`.
std::size_t binaryRequestSize(int32_t id);
// `bytes` holds exactly one message, binaryRequestSize of its id long.
Decoded decodeBinaryRequest(const char* bytes, const CodecParams& params);
Decoded decodeBinaryPoseRequest(const char* bytes, const CodecParams& params);
std::string encodeBinaryRequest(const Request& request, const CodecParams& params);
std::string encodeBinaryPoseRequest(const Request& request, const CodecParams& params);
// Nothing when a pose value does not fit an int32 at the configured scale.
std::optional<std::string> encodeBinaryReply(const Reply& reply, const CodecParams& params);
Reply decodeBinaryReply(const char* bytes, const CodecParams& params);

}  // namespace binpick::robot::detail
