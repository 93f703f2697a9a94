// binpick robot-client [--host H] [--port P] [robot codec options] ...: `binpick robot-client --help`.
// Plays the robot: per cycle TRIGGER (answered once the capture is done), then NEXT until no pick
// is left, printing every pick in millimetres and the robot's orientation convention with the
// time each reply took. --send sends the given requests instead and prints their replies.
#include <cstdio>
#include <iostream>
#include <sstream>

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

std::string describe(const robot::Reply& reply, core::Orientation orientation) {
  std::ostringstream text;
  text << robot::commandKeyword(reply.command) << " " << robot::statusName(reply.status);
  for (const int32_t value : reply.integers) text << " " << value;
  if (reply.T_base_tool) {
    const Eigen::Vector3d mm = reply.T_base_tool->translation() * 1000.0;
    char position[96];
    std::snprintf(position, sizeof(position), " at x %.2f y %.2f z %.2f mm, %s", mm.x(), mm.y(), mm.z(),
                  core::orientationName(orientation).c_str());
    text << position;
    for (const double v : core::orientationValues(reply.T_base_tool->linear(), orientation)) text << " " << v;
  }
  return text.str();
}

struct Session {
  robot::RobotConnection& connection;
  core::Orientation orientation;
  std::chrono::milliseconds timeout;

  robot::Reply send(const robot::Request& request, const std::string& prefix) {
    const core::Stopwatch stopwatch;
    const robot::Reply reply = connection.request(request, timeout);
    const double ms = stopwatch.elapsedMs();
    std::printf("%s%s (%.0f ms)\n", prefix.c_str(), describe(reply, orientation).c_str(), ms);
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

int run(const Arguments& args) {
  const robot::CodecParams codec = codecFromArguments(args);
  const int port = args.integer("--port").value_or(50100);
  const int cycles = args.integer("--cycles").value_or(1);
  if (cycles < 1) throw core::Error("--cycles must be at least 1");
  robot::RobotConnection connection(args.value("--host").value_or("127.0.0.1"), port, codec,
                                    std::chrono::milliseconds(args.integer("--connect-timeout-ms").value_or(10000)));
  Session session{connection, codec.orientation,
                  std::chrono::milliseconds(args.integer("--timeout-ms").value_or(60000))};
  if (const auto script = args.value("--send")) {
    std::istringstream requests(*script);
    std::string request;
    while (std::getline(requests, request, ';')) {
      if (!request.empty()) session.send(parseRequest(request, codec.orientation), "");
    }
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
