#pragma once
// Internal: the pieces RequestDecoder, ReplyDecoder, encodeReply and encodeRequest are made of.
// Each framing's codec works on one complete message; the stream classes do the splitting.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "binpick/io/robot_protocol.hpp"

namespace binpick::robot::detail {

constexpr std::size_t kMaxArgumentLength = 32;
constexpr double kMillimetresPerMetre = 1000.0;  // poses cross the wire in millimetres
// Decoded::command / Reply::command for an unknown ASCII keyword (no enumerator is 0).
constexpr Command kUnknownAsciiCommand = static_cast<Command>(0);
constexpr const char* kUnknownKeyword = "UNKNOWN";

// --- names and arguments (robot_protocol_names.cpp, robot_protocol_arguments.cpp)
std::optional<Command> commandFromKeyword(std::string_view keyword);  // case-insensitive
std::optional<Status> statusFromCode(int64_t code);
bool takesArgument(Command command);  // TRIGGER, FAILED, MODEL
// Why `argument` does not suit `command` (see Request), or "" when it does.
std::string argumentProblem(Command command, const std::optional<std::string>& argument);
// FAILED's object id without leading zeros; other arguments unchanged. Call after the check.
std::optional<std::string> canonicalArgument(Command command,
                                             const std::optional<std::string>& argument);
// A non-negative int32 written as plain decimal digits, or nothing.
std::optional<int32_t> parseNonNegativeInt32(std::string_view digits);
bool isVisibleArgumentCharacter(char c);
// Throws binpick::Error naming the first problem of a request or reply an encoder was handed.
void checkRequest(const Request& request);
void checkReply(const Reply& reply);

// --- quaternion rounding (robot_protocol_rounding.cpp)
// The quaternion w, x, y, z (unit, w >= 0) in whole units of 1 / unitsPerValue: of the 16 ways
// to round each value down or up, the one whose rotation is closest to q's. Rounding each to the
// nearest leaves up to 0.0011 degrees at 5 decimals; the best corner stayed below 0.00093 over
// two million random rotations, within the 0.001 degrees the ASCII defaults promise.
std::array<double, 4> roundQuaternion(const std::vector<double>& q, double unitsPerValue);

// --- ASCII framing (robot_protocol_ascii_request.cpp, robot_protocol_ascii_reply.cpp)
std::vector<std::string_view> splitAtCommas(std::string_view line);  // fields as they are
// `line` is one line without its '\n' (a trailing '\r' is allowed); nothing for a blank line.
std::optional<Decoded> decodeAsciiRequestLine(std::string_view line);
// The BadMessage for a line longer than the limit; `start` is its first max_line_length bytes.
Decoded oversizedAsciiRequest(std::string_view start);
std::string encodeAsciiRequest(const Request& request);
std::string encodeAsciiReply(const Reply& reply, const CodecParams& params);
// `line` without its '\n'; throws binpick::Error naming what was malformed.
Reply decodeAsciiReplyLine(std::string_view line, const CodecParams& params);

// --- binary framing (robot_protocol_binary.cpp); `bytes` holds exactly one message
Decoded decodeBinaryRequest(const char* bytes, ByteOrder order);
std::string encodeBinaryRequest(const Request& request, ByteOrder order);
std::string encodeBinaryReply(const Reply& reply, const CodecParams& params);
Reply decodeBinaryReply(const char* bytes, const CodecParams& params);

}  // namespace binpick::robot::detail
