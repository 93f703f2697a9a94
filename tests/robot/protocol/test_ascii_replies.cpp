// ASCII replies: exact text, the 80-character limit, precision, and decoding them back.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "binpick/robot/protocol.hpp"
#include "protocol_test_support.hpp"
#include "thrown_message.hpp"

namespace binpick::robot {
namespace {

constexpr core::Orientation kAll[] = {core::Orientation::Quaternion, core::Orientation::EulerZYX,
                                      core::Orientation::FixedXYZ, core::Orientation::RotationVector,
                                      core::Orientation::EulerXYZ};

Eigen::Isometry3d pose(double x, double y, double z, const Eigen::Matrix3d& R) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, z);
  T.linear() = R;
  return T;
}

Reply pick(const Eigen::Isometry3d& T_base_tool, std::vector<int32_t> integers = {2, 17, 1}) {
  return Reply{Command::NextPick, Status::Ok, std::move(integers), T_base_tool};
}

Reply decodeReply(const std::string& bytes, const CodecParams& params) {
  ReplyDecoder decoder(params);
  decoder.feed(bytes.data(), bytes.size());
  std::optional<Reply> reply = decoder.next();
  EXPECT_TRUE(reply) << bytes;
  return reply ? *reply : Reply{};
}

CodecParams withOrientation(core::Orientation orientation) {
  CodecParams params;
  params.orientation = orientation;
  return params;
}

TEST(ProtocolAsciiReply, KnownRepliesAreTheseExactLines) {
  const CodecParams params;
  EXPECT_EQ(encodeReply(Reply{Command::Ping, Status::Ok, {}, std::nullopt}, params), "PING,0\r\n");
  EXPECT_EQ(encodeReply(Reply{Command::Status, Status::Ok, {0, 1, 42}, std::nullopt}, params), "STATUS,0,0,1,42\r\n");
  EXPECT_EQ(encodeReply(Reply{Command::NextPick, Status::NoMorePicks, {}, std::nullopt}, params), "NEXT,10\r\n");
  const Eigen::Isometry3d T = pose(0.1, -0.2, 0.3005, Eigen::Matrix3d::Identity());
  EXPECT_EQ(encodeReply(pick(T), params), "NEXT,0,2,17,1,100.00,-200.00,300.50,1.00000,0.00000,0.00000,0.00000\r\n");
  const Eigen::Isometry3d turned = pose(0, 0, -0.000001, test::rotationZ(90));  // -0.001 mm
  EXPECT_EQ(encodeReply(pick(turned, {0, 3, 0}), withOrientation(core::Orientation::EulerZYX)),
            "NEXT,0,0,3,0,0.00,0.00,0.00,90.00000,0.00000,0.00000\r\n");  // no "-0.00"
  EXPECT_EQ(encodeReply(pick(turned, {0, 4, 1}), withOrientation(core::Orientation::FixedXYZ)),
            "NEXT,0,0,4,1,0.00,0.00,0.00,0.00000,0.00000,90.00000\r\n");
  EXPECT_EQ(encodeReply(pick(turned, {0, 4, 1}), withOrientation(core::Orientation::RotationVector)),
            "NEXT,0,0,4,1,0.00,0.00,0.00,0.00000,0.00000,1.57080\r\n");
}

// A robot reads a pick's pose after NEXT's three integers: a pick without all three would put
// x where the grasp id belongs, so it is not sent as one.
TEST(ProtocolAsciiReply, APickGoesOutWithItsThreeIntegersOrNotAtAll) {
  const Eigen::Isometry3d T = pose(0.1, -0.2, 0.3, Eigen::Matrix3d::Identity());
  for (const std::vector<int32_t>& integers : {std::vector<int32_t>{}, {2}, {2, 17}}) {
    EXPECT_EQ(encodeReply(pick(T, integers), CodecParams{}), "NEXT,8\r\n");
    EXPECT_FALSE(encodeReplyIfItFits(pick(T, integers), CodecParams{}));
  }
}

// The report's line: a KUKA cell (euler_zyx) and a robot reading quaternions took the grasp id
// for x. The fields are read by NEXT's shape, and a pose of the wrong length is refused.
TEST(ProtocolAsciiReply, APickIsReadByNextsShapeNeverShifted) {
  const std::string line = "NEXT,0,2,6,1,578.57,101.74,8.46,-96.93005,-0.00920,-179.89643\r\n";
  const Reply kuka = decodeReply(line, withOrientation(core::Orientation::EulerZYX));
  EXPECT_EQ(kuka.integers, (std::vector<int32_t>{2, 6, 1}));
  ASSERT_TRUE(kuka.T_base_tool);
  EXPECT_TRUE(kuka.T_base_tool->translation().isApprox(Eigen::Vector3d(0.57857, 0.10174, 0.00846), 1e-12));
  const std::vector<double> abc = core::orientationValues(kuka.T_base_tool->linear(), core::Orientation::EulerZYX);
  EXPECT_NEAR(abc[0], -96.93005, 1e-9);
  EXPECT_NEAR(abc[1], -0.00920, 1e-9);
  EXPECT_NEAR(abc[2], -179.89643, 1e-9);
  const auto readAs = [&](core::Orientation orientation, const std::string& text) {
    return [=] { decodeReply(text, withOrientation(orientation)); };
  };
  EXPECT_TRUE(test::throwsNaming(readAs(core::Orientation::Quaternion, line),
                                 "NEXT carries 6 pose values after its 3 integers; the quaternion convention has 7: "
                                 "is --orientation the cell's robot.orientation?"));
  const std::string quaternionLine = "NEXT,0,2,6,1,578.57,101.74,8.46,0.04136,-0.47393,0.87939,0.00000\r\n";
  for (core::Orientation threeValues : {core::Orientation::EulerZYX, core::Orientation::FixedXYZ,
                                        core::Orientation::RotationVector, core::Orientation::EulerXYZ}) {
    EXPECT_TRUE(test::throwsNaming(readAs(threeValues, quaternionLine),
                                   "NEXT carries 7 pose values after its 3 integers; the " +
                                       core::orientationName(threeValues) + " convention has 6"));
  }
  // Fewer than NEXT's integers, or a pick that lost one: never read with the integers guessed.
  EXPECT_TRUE(
      test::throwsNaming(readAs(core::Orientation::Quaternion, "NEXT,0,2,6\r\n"), "NEXT ok carries 3 integers"));
  EXPECT_TRUE(test::throwsNaming(readAs(core::Orientation::Quaternion, "NEXT,0,2,6,578.57,101.74,8.46,1,0,0,0\r\n"),
                                 "NEXT carries 6 pose values"));
}

// In every convention a pick sent in any other one with another value count is refused, and
// one with the same count reads with the integers in place.
TEST(ProtocolAsciiReply, EveryConventionRefusesPicksOfAnotherLength) {
  std::mt19937 random(34);
  for (core::Orientation sent : kAll) {
    for (core::Orientation read : kAll) {
      const Eigen::Isometry3d T = test::randomPose(random, 2.0);
      const std::string line = encodeReply(pick(T, {4, 9, 2}), withOrientation(sent));
      const bool sameLength = core::orientationValueCount(sent) == core::orientationValueCount(read);
      if (sameLength) {
        EXPECT_EQ(decodeReply(line, withOrientation(read)).integers, (std::vector<int32_t>{4, 9, 2})) << line;
      } else {
        EXPECT_TRUE(test::throwsNaming([&] { decodeReply(line, withOrientation(read)); },
                                       "is --orientation the cell's robot.orientation?"))
            << line;
      }
    }
  }
}

TEST(ProtocolAsciiReply, RepliesComeBackFromTheirText) {
  std::mt19937 random(31);
  for (core::Orientation orientation : kAll) {
    const CodecParams params = withOrientation(orientation);
    for (int i = 0; i < 2000; ++i) {
      const Eigen::Isometry3d T = test::randomPose(random, 9.99);
      const std::vector<int32_t> integers = {static_cast<int32_t>(random() % 100), static_cast<int32_t>(random() % 100),
                                             static_cast<int32_t>(random() % 100)};
      const std::string line = encodeReply(pick(T, integers), params);
      ASSERT_LE(line.size(), 80u);
      const Reply back = decodeReply(line, params);
      ASSERT_EQ(back.status, Status::Ok) << line;  // full precision fits within +-10 m
      EXPECT_EQ(back.integers, integers);
      ASSERT_TRUE(back.T_base_tool);
      EXPECT_LE((back.T_base_tool->translation() - T.translation()).norm() * 1000.0, 0.01);
      EXPECT_LE(test::angleBetweenDegrees(back.T_base_tool->linear(), T.linear()), 0.001) << line;
    }
  }
  const Reply status = decodeReply("STATUS,0,2,1,7\r\n", CodecParams{});
  EXPECT_EQ(status.command, Command::Status);
  EXPECT_EQ(status.integers, (std::vector<int32_t>{2, 1, 7}));
  EXPECT_FALSE(status.T_base_tool);
}

// Three integers of 99999 and a pose at 99 m: the longest reply the limit must still carry.
TEST(ProtocolAsciiReply, TheWorstCaseFitsEightyCharactersWithReducedPrecision) {
  std::mt19937 random(32);
  const std::vector<int32_t> integers = {99999, 99999, 99999};
  for (core::Orientation orientation : kAll) {
    const CodecParams params = withOrientation(orientation);
    for (int i = 0; i < 2000; ++i) {
      Eigen::Isometry3d T = test::randomPose(random, 99.0);
      if (i == 0) T.translation() = Eigen::Vector3d(-99, -99, -99);
      const std::string line = encodeReply(pick(T, integers), params);
      ASSERT_LE(line.size(), 80u) << line;
      ASSERT_EQ(line.substr(line.size() - 2), "\r\n");
      const Reply back = decodeReply(line, params);
      ASSERT_EQ(back.status, Status::Ok) << line;
      EXPECT_LE((back.T_base_tool->translation() - T.translation()).norm() * 1000.0, 0.1);
      EXPECT_LE(test::angleBetweenDegrees(back.T_base_tool->linear(), T.linear()), 0.2) << line;
    }
  }
}

// Whatever the numbers, a reply never outgrows the limit: it falls back to "KEYWORD,8".
TEST(ProtocolAsciiReply, RepliesThatCannotFitBecomeBadMessagesNeverLongLines) {
  std::mt19937 random(33);
  std::uniform_int_distribution<int32_t> anyInteger(INT32_MIN, INT32_MAX);
  std::uniform_real_distribution<double> exponent(-3.0, 6.0);
  int fallbacks = 0;
  for (core::Orientation orientation : kAll) {
    CodecParams params = withOrientation(orientation);
    for (int i = 0; i < 3000; ++i) {
      params.max_line_length = 16 + random() % 100;
      const Eigen::Isometry3d T = test::randomPose(random, std::pow(10.0, exponent(random)));
      const std::vector<int32_t> integers(random() % 4, anyInteger(random));
      const std::string line = encodeReply(pick(T, integers), params);
      ASSERT_LE(line.size(), params.max_line_length) << line;
      const Reply back = decodeReply(line, params);
      if (back.status == Status::BadMessage) {
        EXPECT_EQ(line, "NEXT,8\r\n");
        ++fallbacks;
      }
    }
  }
  EXPECT_GT(fallbacks, 100);  // the test did reach the fallback
  const Eigen::Isometry3d far = pose(-1e6, -1e6, -1e6, Eigen::Matrix3d::Identity());
  EXPECT_EQ(encodeReply(pick(far, {INT32_MIN, INT32_MIN, INT32_MIN}), CodecParams{}), "NEXT,8\r\n");
  EXPECT_EQ(encodeReply(Reply{Command::Status, Status::Ok, {INT32_MIN, INT32_MIN, INT32_MIN}}, CodecParams{}),
            "STATUS,0,-2147483648,-2147483648,-2147483648\r\n");
  CodecParams narrow;
  narrow.max_line_length = 16;
  EXPECT_EQ(encodeReply(Reply{Command::Status, Status::Ok, {1000, 2000}}, narrow), "STATUS,8\r\n");
}

TEST(ProtocolAsciiReply, MalformedRepliesThrowNamingTheProblem) {
  const CodecParams params;
  const auto decode = [&](const std::string& text) { return [=] { decodeReply(text, params); }; };
  EXPECT_TRUE(test::throwsNaming(decode("PONG,0\r\n"), "unknown keyword"));
  EXPECT_TRUE(test::throwsNaming(decode("PING\r\n"), "no status"));
  EXPECT_TRUE(test::throwsNaming(decode("PING,15\r\n"), "no status code"));
  EXPECT_TRUE(test::throwsNaming(decode("PING,0,1,2,3,4\r\n"), "PING ok carries at most 3 integers and no pose"));
  EXPECT_TRUE(test::throwsNaming(decode("STATUS,0,1.5\r\n"), "no int32"));
  EXPECT_TRUE(test::throwsNaming(decode("TRIGGER,0,1,0,0,0,1,0,0,0\r\n"), "TRIGGER ok carries at most 3 integers"));
  EXPECT_TRUE(test::throwsNaming(decode("NEXT,0\r\n"), "NEXT ok carries 3 integers"));
  EXPECT_TRUE(test::throwsNaming(decode("NEXT,0,1,2,3,x,0,0,1,0,0,0\r\n"), "no finite number"));
  EXPECT_TRUE(test::throwsNaming(decode("NEXT,0,1,2,x,0,0,0,1,0,0,0\r\n"), "no int32"));
  EXPECT_TRUE(test::throwsNaming(decode("NEXT,0,1,2,3,0,0,0,0,0,0,0\r\n"), "zero quaternion"));
  EXPECT_TRUE(test::throwsNaming(decode("PING,0" + std::string(80, ' ') + "\r\n"), "longer than 80"));
  // A malformed line is consumed: the next one still decodes.
  ReplyDecoder decoder(params);
  const std::string bytes = "PONG,0\r\nPING,0\r\n";
  decoder.feed(bytes.data(), bytes.size());
  EXPECT_THROW(decoder.next(), core::Error);
  EXPECT_EQ(decoder.next()->command, Command::Ping);
}

// What `binpick robot-client` and a robot read for a line the service could not read.
TEST(ProtocolAsciiReply, TheErrorReplyReadsBackInBothFramings) {
  const Reply unreadable{Command::Unreadable, Status::BadMessage};
  for (const Framing framing : {Framing::Ascii, Framing::Binary}) {
    CodecParams params;
    params.framing = framing;
    const std::string bytes = encodeReply(unreadable, params);
    if (framing == Framing::Ascii) {
      EXPECT_EQ(bytes, "ERROR,8\r\n");
    }
    const Reply back = decodeReply(bytes, params);
    EXPECT_EQ(back.command, Command::Unreadable);
    EXPECT_EQ(back.status, Status::BadMessage);
    EXPECT_FALSE(back.T_base_tool);
  }
  EXPECT_TRUE(test::throwsNaming(
      [] {
        ReplyDecoder decoder(CodecParams{});
        decoder.feed("ERROR,0\r\n", 9);
        decoder.next();
      },
      "no command"));
}

TEST(ProtocolAsciiReply, RepliesTheEncoderCannotStandForAreRefused) {
  const CodecParams params;
  const Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  EXPECT_TRUE(test::throwsNaming(
      [&] {
        encodeReply(Reply{Command::Status, Status::Ok, {1, 2, 3, 4}, std::nullopt}, params);
      },
      "Reply.integers must be at most 3"));
  EXPECT_TRUE(test::throwsNaming(
      [&] {
        encodeReply(Reply{Command::Trigger, Status::Ok, {}, T}, params);
      },
      "Reply.T_base_tool must be empty"));
  EXPECT_TRUE(test::throwsNaming(
      [&] {
        encodeReply(Reply{Command::NextPick, Status::Ok, {}, std::nullopt}, params);
      },
      "Reply.T_base_tool is missing"));
  Eigen::Isometry3d broken = T;
  broken.translation().x() = std::nan("");
  EXPECT_TRUE(test::throwsNaming([&] { encodeReply(pick(broken), params); }, "must be finite"));
  EXPECT_TRUE(test::throwsNaming(
      [&] {
        encodeReply(Reply{Command::Ping, static_cast<Status>(99), {}, std::nullopt}, params);
      },
      "Reply.status 99"));
  EXPECT_TRUE(test::throwsNaming(
      [&] {
        encodeReply(Reply{static_cast<Command>(42), Status::Ok, {}, std::nullopt}, params);
      },
      "Reply.command 42"));
}

}  // namespace
}  // namespace binpick::robot
