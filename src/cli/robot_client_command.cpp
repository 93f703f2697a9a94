// binpick robot-client [--host H] [--port P] [robot codec options] ...: `binpick robot-client --help`.
// Plays the robot: per cycle TRIGGER (answered once the capture is done), then NEXT until no pick
// is left, printing every reply as the robot reads it, each field by name (a pick in millimetres
// and the --orientation convention's values, at the precision of the framing), with the time
// each reply took. --send sends the given requests instead and prints their replies.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "arguments.hpp"
#include "binpick/core/error.hpp"
#include "binpick/core/stopwatch.hpp"
#include "binpick/robot/robot_connection.hpp"
#include "commands.hpp"
#include "robot_codec_options.hpp"

namespace binpick::cli {
namespace {

using robot::RobotConnection;

using robot::Command;

// "CMD" or "CMD,ARG" -> a request, read as binpickd reads the line; a POSE's values are in the
// --orientation convention, whatever the framing that sends them.
robot::Request parseRequest(const std::string& text, core::Orientation orientation) {
  robot::CodecParams ascii;
  ascii.orientation = orientation;
  robot::RequestDecoder decoder(ascii);
  const std::string line = text + "\n";
  decoder.feed(line.data(), line.size());
  const std::optional<robot::Decoded> decoded = decoder.next();
  if (!decoded || !decoded->request) {
    throw core::Error("--send: '" + text + "' is no request" + (decoded ? ": " + decoded->detail : ""));
  }
  return *decoded->request;
}

// Which server answers. Their STATUS replies tell different things; binpickd answers no POSE,
// so a script that sends one talks to the guided hand-eye session (`calibrate hand-eye --listen`).
enum class Peer { Cell, HandEyeSession };

// One integer of a reply in words: prefix, the value (or its name), suffix: "object 6".
struct IntegerField {
  const char* prefix;
  const char* suffix;
  std::vector<const char*> value_names = {};  // by value, for states
};

// The integers each command's reply carries (docs/robot-protocol.md, "Reply shapes").
std::vector<IntegerField> replyFields(Command command, Peer peer) {
  switch (command) {
    case Command::Status:
      if (peer == Peer::HandEyeSession) {
        return {{"state ", "", {"waiting", "taking a view", "done"}}, {"", " views accepted"}, {"", " wanted"}};
      }
      return {{"state ", "", {"idle", "capturing", "computing"}}, {"model ", ""}, {"", " cycles done"}};
    case Command::Trigger: return {{"cycle ", ""}};
    case Command::NextPick: return {{"", " remaining"}, {"object ", ""}, {"grasp ", ""}};
    case Command::PickFailed: return {{"object ", ""}};
    case Command::SelectModel: return {{"model ", ""}};
    case Command::Pose: return {{"", " views accepted"}, {"", " wanted"}};
    default: return {};  // PING, and replies to what was not understood
  }
}

// The orientation values' names as the robot's pendant shows them (core/orientation.hpp).
std::vector<const char*> orientationValueNames(core::Orientation orientation) {
  switch (orientation) {
    case core::Orientation::Quaternion: return {"q1", "q2", "q3", "q4"};
    case core::Orientation::EulerZYX: return {"A", "B", "C"};
    case core::Orientation::FixedXYZ: return {"W", "P", "R"};
    case core::Orientation::RotationVector:
    case core::Orientation::EulerXYZ: return {"rx", "ry", "rz"};
  }
  return {};
}

// How the replies are read and shown: the codec's convention, at the precision its framing
// carries (ASCII decimals; binary: the decimals of 1 / scale).
struct ReplyFormat {
  robot::Framing framing;
  core::Orientation orientation;
  int position_decimals;
  int orientation_decimals;
  Peer peer;
};

int decimalsOfScale(double scale) { return std::clamp(static_cast<int>(std::ceil(std::log10(scale) - 1e-9)), 0, 9); }

ReplyFormat replyFormat(const robot::CodecParams& codec, Peer peer) {
  if (codec.framing == robot::Framing::Ascii) {
    return {codec.framing, codec.orientation, codec.position_decimals, codec.orientation_decimals, peer};
  }
  return {codec.framing, codec.orientation, decimalsOfScale(codec.position_scale),
          decimalsOfScale(codec.orientation_scale), peer};
}

// Fixed point as the wire writes it: no "-0.00" for a value that rounds to zero.
std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  const std::string written = text;
  if (written.front() == '-' && written.find_first_not_of("-0.") == std::string::npos) return written.substr(1);
  return written;
}

std::string integerText(const IntegerField& field, int32_t value) {
  const bool named = value >= 0 && static_cast<std::size_t>(value) < field.value_names.size();
  return field.prefix +
         (named ? std::string(field.value_names[static_cast<std::size_t>(value)]) : std::to_string(value)) +
         field.suffix;
}

// The integers the reply carries. The binary framing has three fields whatever the command, the
// unused ones 0 (all of them for unknown_command and bad_message): those are left out.
std::vector<int32_t> carriedIntegers(const robot::Reply& reply, std::size_t shape, robot::Framing framing) {
  std::vector<int32_t> integers = reply.integers;
  if (framing != robot::Framing::Binary) return integers;
  const bool carriesNone = reply.status == robot::Status::UnknownCommand || reply.status == robot::Status::BadMessage;
  const std::size_t used = carriesNone ? 0 : shape;
  while (integers.size() > used && integers.back() == 0) integers.pop_back();
  return integers;
}

// "at x 578.57 y 101.74 z 8.46 mm, euler_zyx A -96.93005 B -0.00920 C -179.89643"
std::string poseText(const Eigen::Isometry3d& T_base_tool, const ReplyFormat& format) {
  const Eigen::Vector3d mm = T_base_tool.translation() * 1000.0;
  std::string text = "at x " + fixed(mm.x(), format.position_decimals) + " y " +
                     fixed(mm.y(), format.position_decimals) + " z " + fixed(mm.z(), format.position_decimals) +
                     " mm, " + core::orientationName(format.orientation);
  const std::vector<double> values = core::orientationValues(T_base_tool.linear(), format.orientation);
  const std::vector<const char*> names = orientationValueNames(format.orientation);
  for (std::size_t i = 0; i < values.size(); ++i) {
    text += std::string(" ") + names[i] + " " + fixed(values[i], format.orientation_decimals);
  }
  return text;
}

// "NEXT ok: 2 remaining, object 6, grasp 1, at x ... mm, euler_zyx A ... B ... C ...",
// "TRIGGER ok: cycle 12", "PING ok": every field the robot reads, by name.
std::string describe(const robot::Reply& reply, const ReplyFormat& format) {
  const std::vector<IntegerField> fields = replyFields(reply.command, format.peer);
  std::vector<std::string> parts;
  const std::vector<int32_t> integers = carriedIntegers(reply, fields.size(), format.framing);
  for (std::size_t i = 0; i < integers.size(); ++i) {
    parts.push_back(i < fields.size() ? integerText(fields[i], integers[i]) : "extra " + std::to_string(integers[i]));
  }
  if (reply.T_base_tool) parts.push_back(poseText(*reply.T_base_tool, format));
  std::string text = std::string(robot::commandKeyword(reply.command)) + " " + robot::statusName(reply.status);
  for (std::size_t i = 0; i < parts.size(); ++i) text += (i == 0 ? ": " : ", ") + parts[i];
  return text;
}

struct Session {
  robot::RobotConnection& connection;
  ReplyFormat format;
  std::chrono::milliseconds timeout;

  robot::Reply send(const robot::Request& request, const std::string& prefix) {
    const core::Stopwatch stopwatch;
    const robot::Reply reply = connection.request(request, timeout);
    const double ms = stopwatch.elapsedMs();
    std::printf("%s%s (%.0f ms)\n", prefix.c_str(), describe(reply, format).c_str(), ms);
    std::fflush(stdout);
    return reply;
  }

  // TRIGGER, then NEXT while picks remain. Returns the number of picks received.
  int cycle(int number, const std::optional<std::string>& model) {
    robot::Request trigger{Command::Trigger, model};
    const core::Stopwatch stopwatch;
    const robot::Reply triggered = send(trigger, "cycle " + std::to_string(number) + ": ");
    if (triggered.status != robot::Status::Ok) return 0;
    int picks = 0;
    for (;;) {
      const robot::Reply next = send(robot::Request{Command::NextPick, std::nullopt}, "  ");
      if (next.status != robot::Status::Ok) break;
      ++picks;
      if (!next.integers.empty() && next.integers[0] == 0) break;  // that was the last one
    }
    const double ms = stopwatch.elapsedMs();
    std::printf("cycle %d: %d picks in %.0f ms\n", number, picks, ms);
    return picks;
  }
};

// The requests of a --send script, all read before the first is sent.
std::vector<robot::Request> scriptRequests(const std::string& script, core::Orientation orientation) {
  std::vector<robot::Request> requests;
  std::istringstream texts(script);
  std::string text;
  while (std::getline(texts, text, ';')) {
    if (!text.empty()) requests.push_back(parseRequest(text, orientation));
  }
  return requests;
}

Peer peerOf(const std::vector<robot::Request>& script) {
  const auto isPose = [](const robot::Request& request) { return request.command == Command::Pose; };
  return std::any_of(script.begin(), script.end(), isPose) ? Peer::HandEyeSession : Peer::Cell;
}

int run(const Arguments& args) {
  const robot::CodecParams codec = codecFromArguments(args);
  const int port = args.integer("--port").value_or(50100);
  const int cycles = args.integer("--cycles").value_or(1);
  if (cycles < 1) throw core::Error("--cycles must be at least 1");
  const std::optional<std::string> script = args.value("--send");
  const std::vector<robot::Request> requests =
      script ? scriptRequests(*script, codec.orientation) : std::vector<robot::Request>{};
  robot::RobotConnection connection(args.value("--host").value_or("127.0.0.1"), port, codec,
                                    std::chrono::milliseconds(args.integer("--connect-timeout-ms").value_or(10000)));
  Session session{connection, replyFormat(codec, peerOf(requests)),
                  std::chrono::milliseconds(args.integer("--timeout-ms").value_or(60000))};
  if (script) {
    for (const robot::Request& request : requests) session.send(request, "");
    return 0;
  }
  for (int i = 1; i <= cycles; ++i) session.cycle(i, args.value("--model"));
  return 0;
}

}  // namespace

void addRobotClientCommand(CLI::App& program, CommandTable& table) {
  CLI::App& command = table.add(program, "robot-client", "Play the robot against binpickd: cycles, or requests", run);
  addText(command, "--host", "HOST", "binpickd's address (default 127.0.0.1)");
  addInteger(command, "--port", "N", "binpickd's robot port (default 50100)");
  addInteger(command, "--timeout-ms", "MS", "Wait for each reply at most this long (default 60000)");
  addInteger(command, "--connect-timeout-ms", "MS", "Wait for the connection at most this long (default 10000)");
  CLI::Option* send = addText(command, "--send", "REQUESTS", "Send \"CMD[,ARG];...\" and print the replies instead");
  addInteger(command, "--cycles", "N", "Cycles to run: TRIGGER, then NEXT until no pick is left (default 1)")
      ->excludes(send);
  addText(command, "--model", "NAME", "The part to pick (TRIGGER's argument)")->excludes(send);
  addRobotCodecOptions(command);
}

}  // namespace binpick::cli
