// Binary framing: exact bytes, both byte orders, fixed point, overflow and malformed replies.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "binary_test_support.hpp"
#include "binpick/robot/protocol.hpp"
#include "protocol_test_support.hpp"
#include "thrown_message.hpp"

namespace binpick::robot {
namespace {

constexpr core::Orientation kAll[] = {core::Orientation::Quaternion, core::Orientation::EulerZYX,
                                      core::Orientation::FixedXYZ, core::Orientation::RotationVector,
                                      core::Orientation::EulerXYZ};

Decoded decodeOne(const std::string& message, const CodecParams& params) {
  RequestDecoder decoder(params);
  decoder.feed(message.data(), message.size());
  std::optional<Decoded> decoded = decoder.next();
  EXPECT_TRUE(decoded);
  EXPECT_FALSE(decoder.next());
  return decoded ? *decoded : Decoded{};
}

Reply decodeReply(const std::string& message, const CodecParams& params) {
  ReplyDecoder decoder(params);
  decoder.feed(message.data(), message.size());
  std::optional<Reply> reply = decoder.next();
  EXPECT_TRUE(reply);
  return reply ? *reply : Reply{};
}

TEST(ProtocolBinary, RequestsAreTwoInt32InTheChosenByteOrder) {
  const Decoded little = decodeOne(bytes({3, 0, 0, 0, 5, 0, 0, 0}), binary(ByteOrder::Little));
  ASSERT_TRUE(little.request);
  EXPECT_EQ(little.request->command, Command::Trigger);
  EXPECT_EQ(little.request->argument, "5");
  const Decoded big = decodeOne(bytes({0, 0, 0, 5, 0x7f, 0xff, 0xff, 0xff}), binary(ByteOrder::Big));
  EXPECT_EQ(big.request->command, Command::PickFailed);
  EXPECT_EQ(big.request->argument, "2147483647");
  EXPECT_EQ(encodeRequest(Request{Command::SelectModel, "258"}, binary(ByteOrder::Big)),
            bytes({0, 0, 0, 6, 0, 0, 1, 2}));
  EXPECT_EQ(encodeRequest(Request{Command::Ping, std::nullopt}, binary(ByteOrder::Little)),
            bytes({1, 0, 0, 0, 0xff, 0xff, 0xff, 0xff}));
}

TEST(ProtocolBinary, ArgumentsFollowEachCommandsRules) {
  const CodecParams params = binary(ByteOrder::Big);
  EXPECT_FALSE(decodeOne(bytes({0, 0, 0, 3, 0xff, 0xff, 0xff, 0xff}), params).request->argument);
  // Robots write the argument field for every command: ignored where none is taken.
  const Decoded ping = decodeOne(bytes({0, 0, 0, 1, 0, 0, 0, 9}), params);
  EXPECT_EQ(ping.request->command, Command::Ping);
  EXPECT_FALSE(ping.request->argument);
  const Decoded model = decodeOne(bytes({0, 0, 0, 6, 0x80, 0, 0, 0}), params);
  EXPECT_FALSE(model.request);
  EXPECT_EQ(model.error, Status::BadMessage);
  EXPECT_EQ(model.command, Command::SelectModel);
  EXPECT_TRUE(test::throwsNaming(
      [&] {
        encodeRequest(Request{Command::SelectModel, "bolt"}, params);
      },
      "binary framing carries only an integer"));
  EXPECT_TRUE(test::throwsNaming(
      [&] {
        encodeRequest(Request{Command::Ping, "1"}, params);
      },
      "PING takes no argument"));
}

TEST(ProtocolBinary, UnknownIdsAreEchoedAsReceived) {
  const CodecParams params = binary(ByteOrder::Big);
  const Decoded decoded = decodeOne(bytes({0, 0, 0x01, 0x00, 0, 0, 0, 0}), params);
  EXPECT_EQ(decoded.error, Status::UnknownCommand);
  EXPECT_EQ(decoded.raw_command, 256);
  const std::string reply = encodeReply(Reply{decoded.command, decoded.error}, params);
  EXPECT_EQ(reply.substr(0, 8), bytes({0, 0, 0x01, 0x00, 0, 0, 0, 7}));
  EXPECT_EQ(reply.substr(8), std::string(kBinaryReplySize - 8, '\0'));
  EXPECT_EQ(static_cast<int32_t>(decodeReply(reply, params).command), 256);
}

// Written by hand: NEXT ok, integers 2 17 1, x y z = 100, -200, 300.5 mm at 0.01 mm, identity.
TEST(ProtocolBinary, ABigEndianPickIsTheseBytes) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0.1, -0.2, 0.3005);
  const std::string expected =
      bytes({0,    0,    0,    4,    0, 0, 0,    0,    0, 0, 0,    2,    0, 0, 0, 17, 0, 0, 0, 1, 0, 0, 0x27, 0x10,
             0xff, 0xff, 0xb1, 0xe0, 0, 0, 0x75, 0x62, 0, 0, 0x27, 0x10, 0, 0, 0, 0,  0, 0, 0, 0, 0, 0, 0,    0});
  const Reply reply{Command::NextPick, Status::Ok, {2, 17, 1}, T};
  EXPECT_EQ(encodeReply(reply, binary(ByteOrder::Big)), expected);
  const Reply back = decodeReply(expected, binary(ByteOrder::Big));
  EXPECT_EQ(back.integers, (std::vector<int32_t>{2, 17, 1}));
  EXPECT_TRUE(back.T_base_tool->isApprox(T, 1e-12));
}

TEST(ProtocolBinary, RepliesRoundTripInBothByteOrdersAndEveryConvention) {
  std::mt19937 random(41);
  for (ByteOrder order : {ByteOrder::Little, ByteOrder::Big}) {
    for (core::Orientation orientation : kAll) {
      const CodecParams params = binary(order, orientation);
      for (int i = 0; i < 1000; ++i) {
        const Eigen::Isometry3d T = test::randomPose(random, 20.0);
        const std::vector<int32_t> integers = {static_cast<int32_t>(random()), -7, 0};
        const std::string message = encodeReply(Reply{Command::NextPick, Status::Ok, integers, T}, params);
        ASSERT_EQ(message.size(), kBinaryReplySize);
        const Reply back = decodeReply(message, params);
        ASSERT_EQ(back.status, Status::Ok);
        EXPECT_EQ(back.integers, integers);
        EXPECT_LE((back.T_base_tool->translation() - T.translation()).norm() * 1000.0, 0.01);
        EXPECT_LE(test::angleBetweenDegrees(back.T_base_tool->linear(), T.linear()), 0.01);
      }
      const Reply status =
          decodeReply(encodeReply(Reply{Command::Status, Status::Busy, {1}, std::nullopt}, params), params);
      EXPECT_EQ(status.status, Status::Busy);
      EXPECT_EQ(status.integers, (std::vector<int32_t>{1, 0, 0}));  // the framing has three slots
    }
  }
}

// 30 km at 0.01 mm is 3e9: beyond int32. Sent as BadMessage without integers or pose.
TEST(ProtocolBinary, OverflowingValuesBecomeABadMessage) {
  const CodecParams params = binary(ByteOrder::Little);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation().z() = 30000.0;
  const std::string message = encodeReply(Reply{Command::NextPick, Status::Ok, {1, 2, 3}, T}, params);
  EXPECT_EQ(message, bytes({4, 0, 0, 0, 8, 0, 0, 0}) + std::string(40, '\0'));
  T.translation().z() = 21474.83;  // 2147483000 fits
  EXPECT_EQ(decodeReply(encodeReply(Reply{Command::NextPick, Status::Ok, {}, T}, params), params).status, Status::Ok);
}

TEST(ProtocolBinary, MalformedRepliesThrowNamingTheProblem) {
  const CodecParams params = binary(ByteOrder::Big);
  std::string ping = encodeReply(Reply{Command::Ping, Status::Ok, {}, std::nullopt}, params);
  std::string badStatus = ping;
  badStatus[7] = 15;
  EXPECT_TRUE(test::throwsNaming([&] { decodeReply(badStatus, params); }, "status 15 is no status code"));
  std::string stray = ping;
  stray[kBinaryReplySize - 1] = 1;
  EXPECT_TRUE(test::throwsNaming([&] { decodeReply(stray, params); }, "pose fields are set"));
  std::string unknown = ping;
  unknown[3] = 9;
  EXPECT_TRUE(test::throwsNaming([&] { decodeReply(unknown, params); }, "Reply.command 9"));
  const std::string zeroQuaternion = bytes({0, 0, 0, 4, 0, 0, 0, 0}) + std::string(40, '\0');
  EXPECT_TRUE(test::throwsNaming([&] { decodeReply(zeroQuaternion, params); }, "zero quaternion"));
  CodecParams euler = binary(ByteOrder::Big, core::Orientation::EulerZYX);
  std::string fourth = bytes({0, 0, 0, 4, 0, 0, 0, 0}) + std::string(40, '\0');
  fourth[kBinaryReplySize - 1] = 1;
  EXPECT_TRUE(test::throwsNaming([&] { decodeReply(fourth, euler); }, "fourth orientation field"));
}

// Every convention fills the same fields, so a pick sent in another one is told by its values: a
// fourth value set where three are read, a quaternion far from unit length where four are.
TEST(ProtocolBinary, APickSentInAnotherConventionIsRefusedNamingIt) {
  std::mt19937 random(42);
  for (ByteOrder order : {ByteOrder::Little, ByteOrder::Big}) {
    for (core::Orientation sent : kAll) {
      for (core::Orientation read : kAll) {
        if (core::orientationValueCount(sent) == core::orientationValueCount(read)) continue;
        for (int i = 0; i < 100; ++i) {
          const Eigen::Isometry3d T = test::randomPose(random, 2.0);
          const std::string message =
              encodeReply(Reply{Command::NextPick, Status::Ok, {4, 9, 2}, T}, binary(order, sent));
          EXPECT_TRUE(test::throwsNaming([&] { decodeReply(message, binary(order, read)); },
                                         "is --orientation the cell's robot.orientation?"))
              << core::orientationName(sent) << " read as " << core::orientationName(read);
        }
      }
    }
  }
  // A quaternion on the grid of its scale is unit to within two units: read as it was sent.
  CodecParams coarse = binary(ByteOrder::Big);
  coarse.orientation_scale = 100.0;
  for (int i = 0; i < 1000; ++i) {
    const std::string message =
        encodeReply(Reply{Command::NextPick, Status::Ok, {4, 9, 2}, test::randomPose(random, 2.0)}, coarse);
    EXPECT_NO_THROW(decodeReply(message, coarse));
  }
}

TEST(ProtocolBinary, ParamsAreCheckedNamingTheField) {
  CodecParams params;
  EXPECT_NO_THROW(params.validate());
  params.max_line_length = 15;
  EXPECT_TRUE(test::throwsNaming([&] { params.validate(); }, "robot_protocol.max_line_length must be in [16, 4096]"));
  params = CodecParams{};
  params.position_decimals = 10;
  EXPECT_TRUE(test::throwsNaming([&] { RequestDecoder decoder(params); }, "position_decimals"));
  params = CodecParams{};
  params.orientation_decimals = -1;
  EXPECT_TRUE(test::throwsNaming([&] { ReplyDecoder decoder(params); }, "orientation_decimals"));
  params = CodecParams{};
  params.position_scale = 0.0;
  EXPECT_TRUE(test::throwsNaming([&] { encodeReply(Reply{}, params); }, "position_scale"));
  params = CodecParams{};
  params.orientation_scale = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(test::throwsNaming([&] { encodeRequest(Request{}, params); }, "orientation_scale"));
}

}  // namespace
}  // namespace binpick::robot
