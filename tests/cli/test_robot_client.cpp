// `binpick robot-client` against a scripted robot port: in every orientation convention and
// framing, what it prints for a reply is what the wire carried, field by field and by name; a
// pick sent in another convention is refused naming it, never printed shifted.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "binpick/core/orientation.hpp"
#include "binpick/robot/protocol.hpp"

namespace binpick::test {
namespace {

using robot::CodecParams;
using robot::Command;
using robot::Framing;
using robot::Reply;
using robot::Status;

constexpr core::Orientation kAllOrientations[] = {core::Orientation::Quaternion, core::Orientation::EulerZYX,
                                                  core::Orientation::FixedXYZ, core::Orientation::RotationVector,
                                                  core::Orientation::EulerXYZ};

// The framings a cell can be set to: ASCII, and binary in either byte order.
CodecParams codecOf(Framing framing, robot::ByteOrder order, core::Orientation orientation) {
  CodecParams codec;
  codec.framing = framing;
  codec.byte_order = order;
  codec.orientation = orientation;
  return codec;
}

std::vector<CodecParams> everyFraming(core::Orientation orientation) {
  return {codecOf(Framing::Ascii, robot::ByteOrder::Big, orientation),
          codecOf(Framing::Binary, robot::ByteOrder::Big, orientation),
          codecOf(Framing::Binary, robot::ByteOrder::Little, orientation)};
}

std::string codecName(const CodecParams& codec) {
  const std::string framing = codec.framing == Framing::Ascii             ? "ascii"
                              : codec.byte_order == robot::ByteOrder::Big ? "binary big"
                                                                          : "binary little";
  return framing + ", " + core::orientationName(codec.orientation);
}

// A robot port on loopback that answers each request of one client with the next of `replies`
// (bytes as they go on the wire), whatever was asked: binpickd's side without a cell behind it.
class ScriptedPort {
 public:
  ScriptedPort(const CodecParams& codec, std::vector<std::string> replies)
      : codec_(codec), replies_(std::move(replies)) {
    listener_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t length = sizeof address;
    if (::bind(listener_, reinterpret_cast<sockaddr*>(&address), length) != 0 || ::listen(listener_, 1) != 0 ||
        ::getsockname(listener_, reinterpret_cast<sockaddr*>(&address), &length) != 0) {
      throw std::runtime_error("cannot listen on loopback");
    }
    port_ = ntohs(address.sin_port);
    thread_ = std::thread([this] { serve(); });
  }
  ~ScriptedPort() {
    // Wakes accept() or recv() should the client never have come or never have left.
    ::shutdown(listener_, SHUT_RDWR);
    if (const int client = client_.load(); client >= 0) ::shutdown(client, SHUT_RDWR);
    thread_.join();
    ::close(listener_);
  }
  ScriptedPort(const ScriptedPort&) = delete;
  ScriptedPort& operator=(const ScriptedPort&) = delete;
  int port() const { return port_; }

 private:
  void serve() {
    const int client = ::accept(listener_, nullptr, nullptr);
    if (client < 0) return;
    client_ = client;
    robot::RequestDecoder requests(codec_);
    std::size_t answered = 0;
    char buffer[512];
    ssize_t received = 0;
    while (answered < replies_.size() && (received = ::recv(client, buffer, sizeof buffer, 0)) > 0) {
      requests.feed(buffer, static_cast<std::size_t>(received));
      while (requests.next() && answered < replies_.size()) {
        const std::string& reply = replies_[answered++];
        ::send(client, reply.data(), reply.size(), MSG_NOSIGNAL);
      }
    }
    ::shutdown(client, SHUT_WR);
    while (::recv(client, buffer, sizeof buffer, 0) > 0) {
    }  // until the client is done: it decides when the session ends
    ::close(client);
  }

  CodecParams codec_;
  std::vector<std::string> replies_;
  int listener_ = -1;
  int port_ = 0;
  std::atomic<int> client_{-1};
  std::thread thread_;
};

struct ClientRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
  std::vector<std::string> lines() const {
    std::vector<std::string> all;
    std::istringstream text(output);
    for (std::string line; std::getline(text, line);) all.push_back(line);
    return all;
  }
};

// `binpick robot-client --port PORT` with the codec's options and `options`, e.g. "--cycles 1".
ClientRun robotClient(int port, const CodecParams& codec, const std::string& options) {
  const std::string framing = codec.framing == Framing::Ascii ? "ascii" : "binary";
  const std::string order = codec.byte_order == robot::ByteOrder::Big ? "big" : "little";
  const std::string command = std::string("'") + BINPICK_EXECUTABLE + "' robot-client --port " + std::to_string(port) +
                              " --framing " + framing + " --byte-order " + order + " --orientation " +
                              core::orientationName(codec.orientation) + " " + options + " 2>&1";
  ClientRun run;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run " + command);
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) run.output.append(buffer, n);
  const int status = ::pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

// --- what the wire carries

// A pick as it goes on the wire: its integers and its values (x, y, z in mm, then the
// orientation values), read straight off the bytes.
struct WirePick {
  std::vector<int32_t> integers;
  std::vector<double> values;
};

int32_t int32At(const std::string& bytes, std::size_t field, robot::ByteOrder order) {
  uint32_t bits = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    const auto byte = static_cast<uint32_t>(static_cast<unsigned char>(bytes[4 * field + i]));
    bits |= byte << (order == robot::ByteOrder::Big ? 24 - 8 * i : 8 * i);
  }
  return static_cast<int32_t>(bits);
}

// Binary reply fields: command, status, 3 integers, x, y, z, 4 orientation values.
WirePick binaryWirePick(const std::string& bytes, const CodecParams& codec) {
  WirePick pick;
  for (std::size_t i = 2; i < 5; ++i) pick.integers.push_back(int32At(bytes, i, codec.byte_order));
  for (std::size_t i = 5; i < 8; ++i) pick.values.push_back(int32At(bytes, i, codec.byte_order) / codec.position_scale);
  const auto count = static_cast<std::size_t>(core::orientationValueCount(codec.orientation));
  for (std::size_t i = 8; i < 8 + count; ++i) {
    pick.values.push_back(int32At(bytes, i, codec.byte_order) / codec.orientation_scale);
  }
  return pick;
}

// "NEXT,0,i1,i2,i3,x,y,z,o1,o2,o3[,o4]\r\n"
WirePick asciiWirePick(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream text(line.substr(0, line.find('\r')));
  for (std::string field; std::getline(text, field, ',');) fields.push_back(field);
  WirePick pick;
  for (std::size_t i = 2; i < 5; ++i) pick.integers.push_back(std::stoi(fields[i]));
  for (std::size_t i = 5; i < fields.size(); ++i) pick.values.push_back(std::stod(fields[i]));
  return pick;
}

WirePick wirePick(const std::string& bytes, const CodecParams& codec) {
  return codec.framing == Framing::Ascii ? asciiWirePick(bytes) : binaryWirePick(bytes, codec);
}

// --- what robot-client prints

struct PrintedPick {
  std::vector<int32_t> integers;  // remaining, object, grasp
  std::vector<double> values;     // x, y, z, then the orientation values
  std::string convention;
  std::vector<std::string> names;  // of the orientation values
};

// "  NEXT ok: 2 remaining, object 6, grasp 1, at x 578.57 y 101.74 z 8.46 mm, euler_zyx A ... (0 ms)"
std::optional<PrintedPick> parsePrintedPick(const std::string& line) {
  static const std::regex pick(
      R"(^ *NEXT ok: (-?\d+) remaining, object (-?\d+), grasp (-?\d+), at x (\S+) y (\S+) z (\S+) mm, (\w+)((?: \w+ \S+)+) \(\d+ ms\)$)");
  std::smatch match;
  if (!std::regex_match(line, match, pick)) return std::nullopt;
  PrintedPick printed;
  for (int i = 1; i <= 3; ++i) printed.integers.push_back(std::stoi(match[i]));
  for (int i = 4; i <= 6; ++i) printed.values.push_back(std::stod(match[i]));
  printed.convention = match[7];
  std::istringstream orientation(match[8].str());
  std::string name, value;
  while (orientation >> name >> value) {
    printed.names.push_back(name);
    printed.values.push_back(std::stod(value));
  }
  return printed;
}

std::vector<std::string> valueNames(core::Orientation orientation) {
  switch (orientation) {
    case core::Orientation::Quaternion: return {"q1", "q2", "q3", "q4"};
    case core::Orientation::EulerZYX: return {"A", "B", "C"};
    case core::Orientation::FixedXYZ: return {"W", "P", "R"};
    default: return {"rx", "ry", "rz"};
  }
}

// The smallest step the framing carries for positions (mm) and orientation values.
double positionStep(const CodecParams& codec) {
  return codec.framing == Framing::Ascii ? std::pow(10.0, -codec.position_decimals) : 1.0 / codec.position_scale;
}
double orientationStep(const CodecParams& codec) {
  return codec.framing == Framing::Ascii ? std::pow(10.0, -codec.orientation_decimals) : 1.0 / codec.orientation_scale;
}

// How far a printed value may be from the wire's: half a step of rounding; a quaternion is read
// back normalised, and one on the wire's grid is unit only to within two steps.
double orientationTolerance(const CodecParams& codec) {
  const double steps = codec.orientation == core::Orientation::Quaternion ? 2.5 : 0.5;
  return steps * orientationStep(codec) + 1e-9;
}

// Angles in degrees are the same an integral number of turns apart (180 and -180).
double orientationDifference(double printed, double wire, core::Orientation orientation) {
  const double difference = printed - wire;
  const bool degrees = orientation != core::Orientation::Quaternion && orientation != core::Orientation::RotationVector;
  return degrees ? std::remainder(difference, 360.0) : difference;
}

void expectPrintedAsOnTheWire(const PrintedPick& printed, const WirePick& wire, const CodecParams& codec,
                              const std::string& context) {
  EXPECT_EQ(printed.integers, wire.integers) << context;
  EXPECT_EQ(printed.convention, core::orientationName(codec.orientation)) << context;
  EXPECT_EQ(printed.names, valueNames(codec.orientation)) << context;
  ASSERT_EQ(printed.values.size(), wire.values.size()) << context;
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(printed.values[i], wire.values[i], 0.5 * positionStep(codec) + 1e-9) << "position " << i << context;
  }
  for (std::size_t i = 3; i < wire.values.size(); ++i) {
    EXPECT_LE(std::abs(orientationDifference(printed.values[i], wire.values[i], codec.orientation)),
              orientationTolerance(codec))
        << "orientation value " << i - 3 << " printed " << printed.values[i] << ", wire " << wire.values[i] << context;
  }
}

Eigen::Isometry3d randomPose(std::mt19937& random) {
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> position(-2.0, 2.0);  // metres
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(normal(random), normal(random), normal(random), normal(random))
                   .normalized()
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(position(random), position(random), position(random));
  return T;
}

constexpr int kPicksPerCycle = 12;

// TRIGGER's reply, then kPicksPerCycle picks counting down to the last.
std::vector<std::string> cycleReplies(const CodecParams& codec, std::mt19937& random) {
  std::vector<std::string> replies = {robot::encodeReply(Reply{Command::Trigger, Status::Ok, {12}}, codec)};
  for (int i = 0; i < kPicksPerCycle; ++i) {
    const std::vector<int32_t> integers = {kPicksPerCycle - 1 - i, static_cast<int32_t>(random() % 40),
                                           static_cast<int32_t>(random() % 4)};
    replies.push_back(robot::encodeReply(Reply{Command::NextPick, Status::Ok, integers, randomPose(random)}, codec));
  }
  return replies;
}

TEST(RobotClient, PrintsEveryPickAsTheWireCarriesItInEveryConventionAndFraming) {
  std::mt19937 random(7);
  for (const core::Orientation orientation : kAllOrientations) {
    for (const CodecParams& codec : everyFraming(orientation)) {
      const std::string context = " (" + codecName(codec) + ")";
      const std::vector<std::string> replies = cycleReplies(codec, random);
      const ScriptedPort port(codec, replies);
      const ClientRun run = robotClient(port.port(), codec, "--cycles 1");
      ASSERT_EQ(run.exit_code, 0) << run.output << context;
      const std::vector<std::string> lines = run.lines();
      ASSERT_GE(lines.size(), 1u + kPicksPerCycle) << run.output;
      EXPECT_EQ(lines[0].rfind("cycle 1: TRIGGER ok: cycle 12 (", 0), 0u) << lines[0] << context;
      for (int i = 0; i < kPicksPerCycle; ++i) {
        const std::string& line = lines[static_cast<std::size_t>(1 + i)];
        const std::optional<PrintedPick> printed = parsePrintedPick(line);
        ASSERT_TRUE(printed) << "not a pick as robot-client prints one: '" << line << "'" << context;
        const std::string& bytes = replies[static_cast<std::size_t>(1 + i)];
        expectPrintedAsOnTheWire(*printed, wirePick(bytes, codec), codec, context + " '" + line + "'");
      }
    }
  }
}

// The reply of the report that robot-client printed with every field shifted by one.
TEST(RobotClient, PrintsThePickOfAKukaCellAsItsLineReads) {
  const std::string line = "NEXT,0,2,6,1,578.57,101.74,8.46,-96.93005,-0.00920,-179.89643\r\n";
  const CodecParams euler = codecOf(Framing::Ascii, robot::ByteOrder::Big, core::Orientation::EulerZYX);
  const ScriptedPort port(euler, {line});
  const ClientRun run = robotClient(port.port(), euler, "--send NEXT");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(run.output.rfind("NEXT ok: 2 remaining, object 6, grasp 1, at x 578.57 y 101.74 z 8.46 mm, "
                             "euler_zyx A -96.93005 B -0.00920 C -179.89643 (",
                             0),
            0u)
      << run.output;
}

// What the robot would hear as something else is an error naming the conventions, exit 1.
TEST(RobotClient, RefusesAPickSentInAnotherConvention) {
  std::mt19937 random(8);
  Eigen::Isometry3d T = randomPose(random);
  T.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.2, -0.5, 0.8).normalized()).toRotationMatrix();
  struct Case {
    core::Orientation sent, read;
    std::string named;
  };
  const std::vector<Case> cases = {
      {core::Orientation::EulerZYX, core::Orientation::Quaternion, "the quaternion convention has 7"},
      {core::Orientation::Quaternion, core::Orientation::FixedXYZ, "the fixed_xyz convention has 6"},
  };
  for (const Case& c : cases) {
    for (const CodecParams& cell : everyFraming(c.sent)) {
      CodecParams robotSide = cell;
      robotSide.orientation = c.read;
      const std::string context = " (sent " + codecName(cell) + ", read in " + core::orientationName(c.read) + ")";
      const ScriptedPort port(cell, {robot::encodeReply(Reply{Command::NextPick, Status::Ok, {2, 6, 1}, T}, cell)});
      const ClientRun run = robotClient(port.port(), robotSide, "--send NEXT");
      EXPECT_EQ(run.exit_code, 1) << run.output << context;
      EXPECT_EQ(run.output.find("NEXT ok"), std::string::npos) << run.output << context;
      EXPECT_NE(run.output.find("is --orientation the cell's robot.orientation?"), std::string::npos)
          << run.output << context;
      if (cell.framing == Framing::Ascii) {
        EXPECT_NE(run.output.find(c.named), std::string::npos) << run.output;
      }
    }
  }
}

// Every reply's integers by name, the same in both framings (binary pads with unused zeros).
TEST(RobotClient, NamesTheFieldsOfEveryReply) {
  for (const CodecParams& codec : everyFraming(core::Orientation::Quaternion)) {
    const std::vector<Reply> replies = {
        Reply{Command::Ping, Status::Ok},
        Reply{Command::Status, Status::Ok, {0, 0, 3}},
        Reply{Command::Trigger, Status::Busy, {0}},
        Reply{Command::NextPick, Status::NoMorePicks, {0, -1, -1}},
        Reply{Command::PickFailed, Status::Ok, {3}},
        Reply{Command::SelectModel, Status::UnknownModel, {1}},
        Reply{Command::NextPick, Status::BadMessage},
    };
    std::vector<std::string> bytes;
    for (const Reply& reply : replies) bytes.push_back(robot::encodeReply(reply, codec));
    const ScriptedPort port(codec, bytes);
    const ClientRun run = robotClient(port.port(), codec, "--send 'PING;STATUS;TRIGGER;NEXT;FAILED;MODEL,9;NEXT'");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const std::vector<std::string> expected = {"PING ok (",
                                               "STATUS ok: state idle, model 0, 3 cycles done (",
                                               "TRIGGER busy: cycle 0 (",
                                               "NEXT no_more_picks: 0 remaining, object -1, grasp -1 (",
                                               "FAILED ok: object 3 (",
                                               "MODEL unknown_model: model 1 (",
                                               "NEXT bad_message ("};
    const std::vector<std::string> lines = run.lines();
    ASSERT_EQ(lines.size(), expected.size()) << run.output;
    for (std::size_t i = 0; i < expected.size(); ++i) {
      EXPECT_EQ(lines[i].rfind(expected[i], 0), 0u) << lines[i] << " (" << codecName(codec) << ")";
    }
  }
}

// A script with a POSE talks to the guided hand-eye session, whose STATUS counts views.
TEST(RobotClient, NamesTheHandEyeSessionsFields) {
  const CodecParams codec = codecOf(Framing::Ascii, robot::ByteOrder::Big, core::Orientation::EulerZYX);
  const ScriptedPort port(codec, {"STATUS,0,0,0,6\r\n", "POSE,0,1,6\r\n"});
  const ClientRun run =
      robotClient(port.port(), codec, "--send 'STATUS;POSE,612.53,-75.27,-142.07,-1.57953,17.61323,-3.5'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::vector<std::string> lines = run.lines();
  ASSERT_EQ(lines.size(), 2u) << run.output;
  EXPECT_EQ(lines[0].rfind("STATUS ok: state waiting, 0 views accepted, 6 wanted (", 0), 0u) << lines[0];
  EXPECT_EQ(lines[1].rfind("POSE ok: 1 views accepted, 6 wanted (", 0), 0u) << lines[1];
}

}  // namespace
}  // namespace binpick::test
