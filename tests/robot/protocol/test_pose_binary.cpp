// POSE in the binary framing: the one longer request, its exact bytes, every convention in both
// byte orders, and a decoder that stays in step around it.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "binary_test_support.hpp"
#include "binpick/robot/protocol.hpp"
#include "protocol_test_support.hpp"
#include "thrown_message.hpp"

namespace binpick::robot {
namespace {

std::vector<Decoded> decodeAll(const std::string& message, const CodecParams& params) {
  RequestDecoder decoder(params);
  decoder.feed(message.data(), message.size());
  std::vector<Decoded> all;
  while (std::optional<Decoded> decoded = decoder.next()) all.push_back(*decoded);
  return all;
}

Request poseRequest(const Eigen::Isometry3d& T_base_flange) {
  return Request{Command::Pose, std::nullopt, T_base_flange};
}

// Written by hand: POSE, x y z = 100, -200, 300.5 mm at 0.01 mm, the identity quaternion.
const std::string kPoseBytes = bytes({0, 0, 0,    7,    0, 0, 0x27, 0x10, 0xff, 0xff, 0xb1, 0xe0, 0, 0, 0x75, 0x62,
                                      0, 0, 0x27, 0x10, 0, 0, 0,    0,    0,    0,    0,    0,    0, 0, 0,    0});

TEST(ProtocolPoseBinary, APoseIsTheseBytesAndThePingAfterItStillDecodes) {
  ASSERT_EQ(kPoseBytes.size(), kBinaryPoseRequestSize);
  const CodecParams params = binary(ByteOrder::Big);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0.1, -0.2, 0.3005);
  EXPECT_EQ(encodeRequest(poseRequest(T), params), kPoseBytes);
  const std::string ping = encodeRequest(Request{Command::Ping}, params);
  const std::vector<Decoded> all = decodeAll(kPoseBytes + ping, params);
  ASSERT_EQ(all.size(), 2u);
  ASSERT_TRUE(all[0].request) << all[0].detail;
  EXPECT_EQ(all[0].raw_command, 7);
  EXPECT_TRUE(all[0].request->T_base_flange->isApprox(T, 1e-12));
  EXPECT_EQ(all[1].request->command, Command::Ping);
}

TEST(ProtocolPoseBinary, AnIncompletePoseWaitsForItsLastByte) {
  RequestDecoder decoder(binary(ByteOrder::Big));
  decoder.feed(kPoseBytes.data(), kPoseBytes.size() - 1);
  EXPECT_FALSE(decoder.next());
  EXPECT_EQ(decoder.buffered(), kMaxBinaryRequestSize - 1);
  decoder.feed(kPoseBytes.data() + kPoseBytes.size() - 1, 1);
  const std::optional<Decoded> decoded = decoder.next();
  ASSERT_TRUE(decoded);
  EXPECT_TRUE(decoded->request);
  EXPECT_EQ(decoder.buffered(), 0u);
}

TEST(ProtocolPoseBinary, EveryConventionRoundTripsInBothByteOrders) {
  std::mt19937 random(72);
  for (ByteOrder order : {ByteOrder::Little, ByteOrder::Big}) {
    for (core::Orientation orientation : test::kAllOrientations) {
      const CodecParams params = binary(order, orientation);
      for (int i = 0; i < 1000; ++i) {
        const Eigen::Isometry3d T = test::randomPose(random, 20.0);
        const std::string message = encodeRequest(poseRequest(T), params);
        ASSERT_EQ(message.size(), kBinaryPoseRequestSize);
        // Unused orientation fields are 0: the fourth value exists only for quaternions.
        const bool fourth = message.substr(7 * 4) != std::string(4, '\0');
        ASSERT_TRUE(orientation == core::Orientation::Quaternion || !fourth);
        const std::vector<Decoded> back = decodeAll(message, params);
        ASSERT_EQ(back.size(), 1u);
        ASSERT_TRUE(back[0].request) << back[0].detail;
        const Eigen::Isometry3d& R = *back[0].request->T_base_flange;
        EXPECT_LE((R.translation() - T.translation()).norm() * 1000.0, 0.01);
        EXPECT_LE(test::angleBetweenDegrees(R.linear(), T.linear()), 0.01);
      }
    }
  }
}

TEST(ProtocolPoseBinary, MalformedPosesAreBadMessagesAndTheStreamGoesOn) {
  const CodecParams euler = binary(ByteOrder::Big, core::Orientation::EulerZYX);
  std::string fourth = kPoseBytes;  // a fourth value where the convention has three
  fourth.back() = 1;
  const std::string ping = encodeRequest(Request{Command::Ping}, euler);
  const std::vector<Decoded> all = decodeAll(fourth + ping, euler);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].error, Status::BadMessage);
  EXPECT_EQ(all[0].command, Command::Pose);
  EXPECT_NE(all[0].detail.find("unused orientation field"), std::string::npos);
  EXPECT_EQ(all[1].request->command, Command::Ping);
  const std::string zero = bytes({0, 0, 0, 7}) + std::string(28, '\0');
  const std::vector<Decoded> zeroQuaternion = decodeAll(zero, binary(ByteOrder::Big));
  ASSERT_EQ(zeroQuaternion.size(), 1u);
  EXPECT_EQ(zeroQuaternion[0].error, Status::BadMessage);
  EXPECT_NE(zeroQuaternion[0].detail.find("zero quaternion"), std::string::npos);
  // Its reply is the usual 48 bytes: POSE, bad_message.
  const std::string reply = encodeReply(Reply{zeroQuaternion[0].command, zeroQuaternion[0].error}, euler);
  EXPECT_EQ(reply.substr(0, 8), bytes({0, 0, 0, 7, 0, 0, 0, 8}));
}

TEST(ProtocolPoseBinary, PosesBeyondInt32AreRefusedByTheEncoder) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation().z() = 30000.0;  // 3e9 units of 0.01 mm
  EXPECT_TRUE(test::throwsNaming([&] { encodeRequest(poseRequest(T), binary(ByteOrder::Little)); }, "does not fit"));
}

TEST(ProtocolPoseBinary, RepliesCarryTheViewCounts) {
  const CodecParams params = binary(ByteOrder::Little);
  const std::string message = encodeReply(Reply{Command::Pose, Status::BoardNotFound, {4, 12}}, params);
  EXPECT_EQ(message.substr(0, 20), bytes({7, 0, 0, 0, 14, 0, 0, 0, 4, 0, 0, 0, 12, 0, 0, 0, 0, 0, 0, 0}));
  ReplyDecoder decoder(params);
  decoder.feed(message.data(), message.size());
  const std::optional<Reply> reply = decoder.next();
  ASSERT_TRUE(reply);
  EXPECT_EQ(reply->status, Status::BoardNotFound);
  EXPECT_EQ(reply->integers, (std::vector<int32_t>{4, 12, 0}));
}

}  // namespace
}  // namespace binpick::robot
