// POSE in the ASCII framing: the robot's flange pose in every orientation convention, the exact
// lines, the 80-character limit, and the malformed lines a robot program may send.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "binpick/robot/protocol.hpp"
#include "protocol_test_support.hpp"
#include "thrown_message.hpp"

namespace binpick::robot {
namespace {

CodecParams withOrientation(core::Orientation orientation) {
  CodecParams params;
  params.orientation = orientation;
  return params;
}

std::vector<Decoded> decodeAll(const std::string& bytes, const CodecParams& params) {
  RequestDecoder decoder(params);
  decoder.feed(bytes.data(), bytes.size());
  std::vector<Decoded> all;
  while (std::optional<Decoded> decoded = decoder.next()) all.push_back(*decoded);
  return all;
}

Decoded decodeOne(const std::string& line, const CodecParams& params) {
  const std::vector<Decoded> all = decodeAll(line, params);
  EXPECT_EQ(all.size(), 1u) << line;
  return all.empty() ? Decoded{} : all.front();
}

void expectBadPose(const std::string& line, const CodecParams& params) {
  const Decoded decoded = decodeOne(line, params);
  EXPECT_FALSE(decoded.request) << line;
  EXPECT_EQ(decoded.error, Status::BadMessage) << line;
  EXPECT_EQ(decoded.command, Command::Pose) << line;
  EXPECT_FALSE(decoded.detail.empty());
  // What the robot hears back.
  EXPECT_EQ(encodeReply(Reply{decoded.command, decoded.error}, params), "POSE,8\r\n");
}

Request poseRequest(const Eigen::Isometry3d& T_base_flange) {
  return Request{Command::Pose, std::nullopt, T_base_flange};
}

TEST(ProtocolPoseAscii, ThePendantsNumbersBecomeTheFlangePose) {
  const Decoded kuka = decodeOne("POSE,600,0,400,180,0,0\r\n", withOrientation(core::Orientation::EulerZYX));
  ASSERT_TRUE(kuka.request) << kuka.detail;
  EXPECT_EQ(kuka.command, Command::Pose);
  EXPECT_FALSE(kuka.request->argument);
  ASSERT_TRUE(kuka.request->T_base_flange);
  const Eigen::Isometry3d& T = *kuka.request->T_base_flange;
  EXPECT_TRUE(T.translation().isApprox(Eigen::Vector3d(0.6, 0.0, 0.4), 1e-12));
  EXPECT_LT(test::angleBetweenDegrees(T.linear(), test::rotationZ(180)), 1e-9);
  // Keyword case, spaces and a quaternion's four values.
  const Decoded abb = decodeOne(" pose , -12.5 ,7, 1e3 ,0.70711,0.70711,0,0\n", CodecParams{});
  ASSERT_TRUE(abb.request) << abb.detail;
  EXPECT_TRUE(abb.request->T_base_flange->translation().isApprox(Eigen::Vector3d(-0.0125, 0.007, 1.0), 1e-12));
  EXPECT_LT(test::angleBetweenDegrees(abb.request->T_base_flange->linear(), test::rotationX(90)), 1e-3);
}

TEST(ProtocolPoseAscii, EncodedPosesAreTheseLines) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0.6, -0.0000001, 0.4);
  EXPECT_EQ(encodeRequest(poseRequest(T), CodecParams{}),
            "POSE,600.00,0.00,400.00,1.00000,0.00000,0.00000,0.00000\r\n");  // no "-0.00"
  T.linear() = test::rotationZ(180);
  EXPECT_EQ(encodeRequest(poseRequest(T), withOrientation(core::Orientation::EulerZYX)),
            "POSE,600.00,0.00,400.00,180.00000,0.00000,0.00000\r\n");
  EXPECT_EQ(encodeRequest(poseRequest(T), withOrientation(core::Orientation::RotationVector)),
            "POSE,600.00,0.00,400.00,0.00000,0.00000,3.14159\r\n");
}

// Every convention's value count, and the promise of the header: within +-10 m a pose fits 80
// characters and reads back within 0.01 mm and 0.001 degrees.
TEST(ProtocolPoseAscii, EveryConventionRoundTripsWithinTheLineLimit) {
  std::mt19937 random(71);
  for (core::Orientation orientation : test::kAllOrientations) {
    const CodecParams params = withOrientation(orientation);
    for (int i = 0; i < 2000; ++i) {
      const Eigen::Isometry3d T = test::randomPose(random, i % 2 == 0 ? 9.99999 : 1.0);
      const std::string line = encodeRequest(poseRequest(T), params);
      ASSERT_LE(line.size(), params.max_line_length) << line;
      const std::size_t commas = static_cast<std::size_t>(std::count(line.begin(), line.end(), ','));
      ASSERT_EQ(commas, 3u + static_cast<std::size_t>(core::orientationValueCount(orientation))) << line;
      const Decoded back = decodeOne(line, params);
      ASSERT_TRUE(back.request) << line << ": " << back.detail;
      const Eigen::Isometry3d& R = *back.request->T_base_flange;
      EXPECT_LE((R.translation() - T.translation()).norm() * 1000.0, 0.01) << line;
      EXPECT_LE(test::angleBetweenDegrees(R.linear(), T.linear()), 0.001) << line;
    }
  }
}

TEST(ProtocolPoseAscii, WrongValueCountsAreBadMessages) {
  for (core::Orientation orientation : test::kAllOrientations) {
    const CodecParams params = withOrientation(orientation);
    const int count = 3 + core::orientationValueCount(orientation);
    std::string line = "POSE";
    for (int i = 0; i <= count + 1; ++i) {
      const Decoded decoded = decodeOne(line + "\r\n", params);
      EXPECT_EQ(decoded.request.has_value(), i == count) << core::orientationName(orientation) << " " << line;
      if (i != count) expectBadPose(line + "\r\n", params);
      line += i % 2 == 0 ? ",0.5" : ",1";
    }
  }
}

TEST(ProtocolPoseAscii, ValuesThatAreNoFiniteNumbersAreBadMessages) {
  const CodecParams params = withOrientation(core::Orientation::EulerZYX);
  expectBadPose("POSE,nan,0,400,180,0,0\r\n", params);
  expectBadPose("POSE,600,0,400,NaN,0,0\r\n", params);
  expectBadPose("POSE,600,0,inf,180,0,0\r\n", params);
  expectBadPose("POSE,600,0,1e999,180,0,0\r\n", params);  // beyond double
  expectBadPose("POSE,600,,400,180,0,0\r\n", params);
  expectBadPose("POSE,600,0,400,180,0,0x1\r\n", params);
  expectBadPose("POSE,+600,0,400,180,0,0\r\n", params);
  expectBadPose("POSE,600 mm,0,400,180,0,0\r\n", params);
  expectBadPose("POSE,600,0,400,180,0,0,\r\n", params);
  expectBadPose("POSE,0,0,0,0,0,0,0\r\n", CodecParams{});  // the zero quaternion
}

TEST(ProtocolPoseAscii, ALineBeyondTheLimitIsOneBadMessageThenTheNextLineCounts) {
  const CodecParams params = withOrientation(core::Orientation::EulerZYX);
  const std::string longest = "POSE,600.0000000,0,400,180,0,0" + std::string(48, ' ') + "\r\n";
  ASSERT_EQ(longest.size(), 80u);
  EXPECT_TRUE(decodeOne(longest, params).request);
  const std::string tooLong = "POSE,600.00000000,0,400,180,0,0" + std::string(48, ' ') + "\r\n";
  const std::vector<Decoded> all = decodeAll(tooLong + "PING\r\n", params);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].error, Status::BadMessage);
  EXPECT_EQ(all[0].command, Command::Pose);  // its comma came within the limit
  EXPECT_EQ(all[1].request->command, Command::Ping);
}

TEST(ProtocolPoseAscii, EncoderRefusesPosesThatDoNotBelong) {
  const CodecParams params;
  EXPECT_TRUE(test::throwsNaming([&] { encodeRequest(Request{Command::Pose}, params); }, "T_base_flange is missing"));
  EXPECT_TRUE(test::throwsNaming(
      [&] {
        encodeRequest(Request{Command::Ping, std::nullopt, Eigen::Isometry3d::Identity()}, params);
      },
      "must be empty unless POSE"));
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation().x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(test::throwsNaming([&] { encodeRequest(poseRequest(T), params); }, "finite"));
  T.translation() = Eigen::Vector3d::Constant(1e9);  // 1e12 mm: 89 characters
  EXPECT_TRUE(test::throwsNaming([&] { encodeRequest(poseRequest(T), params); }, "max_line_length"));
  T.translation() = Eigen::Vector3d(1e13, 0.0, 0.0);  // beyond what any line could hold
  EXPECT_TRUE(test::throwsNaming([&] { encodeRequest(poseRequest(T), params); }, "too far out"));
}

TEST(ProtocolPoseAscii, RepliesCarryTheViewCountsAndBoardNotFound) {
  const CodecParams params;
  EXPECT_EQ(encodeReply(Reply{Command::Pose, Status::Ok, {3, 12}}, params), "POSE,0,3,12\r\n");
  const std::string missed = encodeReply(Reply{Command::Pose, Status::BoardNotFound, {3, 12}}, params);
  EXPECT_EQ(missed, "POSE,14,3,12\r\n");
  EXPECT_EQ(std::string(statusName(Status::BoardNotFound)), "board_not_found");
  ReplyDecoder decoder(params);
  decoder.feed(missed.data(), missed.size());
  const std::optional<Reply> reply = decoder.next();
  ASSERT_TRUE(reply);
  EXPECT_EQ(reply->command, Command::Pose);
  EXPECT_EQ(reply->status, Status::BoardNotFound);
  EXPECT_EQ(reply->integers, (std::vector<int32_t>{3, 12}));
  EXPECT_FALSE(reply->T_base_tool);
}

}  // namespace
}  // namespace binpick::robot
