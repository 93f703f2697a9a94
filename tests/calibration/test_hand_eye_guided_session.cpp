// The guided hand-eye session without a network: POSE requests in, replies and a views directory
// out, with the board found, not found, a failing camera, and requests arriving mid-view.
#include <gtest/gtest.h>

#include <filesystem>
#include <thread>

#include "binpick/calibration/hand_eye_views.hpp"
#include "binpick/calibration/robot_pose_file.hpp"
#include "binpick/io/image_file.hpp"
#include "hand_eye_guided_support.hpp"
#include "temp_directory_test.hpp"

namespace binpick::cli {
namespace {

namespace fs = std::filesystem;
using robot::Command;
using robot::Status;
using testing::boardImage;
using testing::pose;
using testing::request;

constexpr robot::ClientId kRobot = 1;
constexpr robot::ClientId kMonitor = 2;

bool sameImage(const cv::Mat& a, const std::string& path) {
  const cv::Mat b = io::readImageFile(path);
  return !b.empty() && a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

std::vector<std::string> pngsIn(const fs::path& directory) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(directory)) {
    if (entry.path().extension() == ".png") names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

class GuidedSession : public test::TempDirectoryTest {
 protected:
  void start(int wanted, std::chrono::milliseconds grace = std::chrono::hours(1)) {
    GuidedSessionParams params;
    params.wanted = wanted;
    params.camera = testing::testCamera();
    params.final_reply_grace = grace;
    recorder = std::make_unique<GuidedViewRecorder>(root(), core::Orientation::EulerZYX);
    session = std::make_unique<HandEyeGuidedSession>(params, *recorder, camera, replies.sink());
  }
  robot::Reply ask(const robot::Request& r, robot::ClientId client = kRobot) {
    session->handle(client, r);
    return replies.next(client);
  }
  void expectPoseReply(const robot::Reply& reply, Status status, int accepted, int wanted) {
    EXPECT_EQ(reply.command, Command::Pose);
    EXPECT_EQ(reply.status, status) << robot::statusName(reply.status);
    EXPECT_EQ(reply.integers, (std::vector<int32_t>{accepted, wanted}));
  }

  testing::ScriptedCamera camera;
  testing::Replies replies;
  std::unique_ptr<GuidedViewRecorder> recorder;
  std::unique_ptr<HandEyeGuidedSession> session;
};

TEST_F(GuidedSession, AcceptedViewsAreADirectoryTheFileModeReads) {
  start(3);
  std::vector<robot::Request> sent;
  for (int i = 0; i < 3; ++i) {
    camera.queue(boardImage(10 * i));
    sent.push_back(pose(0.5 + 0.1 * i, 20.0 * i));
    expectPoseReply(ask(sent.back()), Status::Ok, i + 1, 3);
  }
  EXPECT_TRUE(session->complete());
  const std::vector<calibration::HandEyeViewFile> views = calibration::listHandEyeViews(root());
  ASSERT_EQ(views.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(views[i].name, "view_00" + std::to_string(i));
    // poses.txt keeps 1e-4 mm and 1e-9 of the orientation values.
    EXPECT_TRUE(views[i].T_base_flange.isApprox(*sent[i].T_base_flange, 1e-7)) << i;
    EXPECT_TRUE(sameImage(boardImage(10 * i), views[i].image_path)) << i;
  }
  EXPECT_EQ(calibration::readRobotPoseFile(pathOf("received.txt")).poses.size(), 3u);
}

TEST_F(GuidedSession, AnImageWithoutABoardIsKeptAsideAndAnswered) {
  start(2);
  camera.queue(testing::blankImage());
  const robot::Request lost = pose(0.6, 10.0);
  expectPoseReply(ask(lost), Status::BoardNotFound, 0, 2);
  EXPECT_TRUE(pngsIn(root()).empty());  // the file mode would take any DIR/*.png for a view
  EXPECT_TRUE(sameImage(testing::blankImage(), pathOf("rejected/attempt_001.png")));
  const calibration::RobotPoseFile rejected = calibration::readRobotPoseFile(pathOf("rejected/poses.txt"));
  ASSERT_EQ(rejected.poses.size(), 1u);
  EXPECT_EQ(rejected.poses[0].view, "attempt_001");
  EXPECT_TRUE(rejected.poses[0].T_base_flange.isApprox(*lost.T_base_flange, 1e-7));
  camera.queue(boardImage());
  expectPoseReply(ask(pose(0.7)), Status::Ok, 1, 2);  // the session goes on
  EXPECT_EQ(pngsIn(root()), std::vector<std::string>{"view_000.png"});
}

TEST_F(GuidedSession, CameraFailuresAndWrongSizesAreAnsweredAndTheSessionGoesOn) {
  start(1);
  camera.queueFailure("camera FAKE: timeout");
  expectPoseReply(ask(pose(0.5)), Status::NoImage, 0, 1);
  camera.queue(cv::Mat(100, 100, CV_8UC1, cv::Scalar(0)));
  expectPoseReply(ask(pose(0.5)), Status::CalibrationMissing, 0, 1);
  EXPECT_TRUE(fs::exists(pathOf("rejected/attempt_002.png")));
  camera.queue(boardImage());
  expectPoseReply(ask(pose(0.5)), Status::Ok, 1, 1);
  // Every pose was journaled, the one without an image too.
  EXPECT_EQ(calibration::readRobotPoseFile(pathOf("received.txt")).poses.size(), 3u);
}

TEST_F(GuidedSession, PingAndStatusAreAnsweredWhileAViewIsTaken) {
  start(2);
  camera.hold();
  camera.queue(boardImage());
  session->handle(kRobot, pose(0.5));
  camera.waitUntilGrabbing();
  EXPECT_EQ(ask(request(Command::Ping), kMonitor).status, Status::Ok);
  const robot::Reply status = ask(request(Command::Status), kMonitor);
  EXPECT_EQ(status.status, Status::Ok);
  EXPECT_EQ(status.integers, (std::vector<int32_t>{1, 0, 2}));  // taking a view, 0 of 2
  EXPECT_EQ(replies.waiting(kRobot), 0u);
  camera.release();
  expectPoseReply(replies.next(kRobot), Status::Ok, 1, 2);
  EXPECT_EQ(ask(request(Command::Status), kMonitor).integers, (std::vector<int32_t>{0, 1, 2}));
}

TEST_F(GuidedSession, OtherCommandsAreUnknownAndViewsBeyondTheCountAreNotTaken) {
  start(1);
  for (Command command : {Command::Trigger, Command::NextPick, Command::PickFailed, Command::SelectModel}) {
    const robot::Reply reply = ask(request(command));
    EXPECT_EQ(reply.command, command);
    EXPECT_EQ(reply.status, Status::UnknownCommand);
  }
  camera.queue(boardImage());
  expectPoseReply(ask(pose(0.5)), Status::Ok, 1, 1);
  expectPoseReply(ask(pose(0.6)), Status::Busy, 1, 1);
  EXPECT_EQ(ask(request(Command::Status)).integers, (std::vector<int32_t>{2, 1, 1}));
  EXPECT_EQ(calibration::readRobotPoseFile(pathOf("received.txt")).poses.size(), 1u);
}

TEST_F(GuidedSession, FinishedOnceTheRobotHasReadItsLastReply) {
  start(1);
  camera.queue(boardImage());
  expectPoseReply(ask(pose(0.5)), Status::Ok, 1, 1);
  EXPECT_TRUE(session->complete());
  EXPECT_FALSE(session->finished());  // the reply may still be on its way
  session->disconnected(kMonitor);
  EXPECT_FALSE(session->finished());
  session->disconnected(kRobot);
  EXPECT_TRUE(session->finished());
}

TEST_F(GuidedSession, WithoutGraceTheLastViewFinishesTheSession) {
  start(1, std::chrono::milliseconds(0));
  camera.queue(boardImage());
  expectPoseReply(ask(pose(0.5)), Status::Ok, 1, 1);
  EXPECT_TRUE(session->finished());
}

TEST_F(GuidedSession, StoppingFinishesTheViewInHandAndDropsTheWaitingOnes) {
  start(3);
  camera.hold();
  camera.queue(boardImage());
  camera.queue(boardImage(20));
  session->handle(kRobot, pose(0.5));
  camera.waitUntilGrabbing();
  session->handle(kMonitor, pose(0.6));  // waits behind the first
  session->disconnected(kMonitor);       // ... and is dropped: that robot has gone
  std::thread stopping([this] { session->stop(); });
  camera.release();
  stopping.join();
  EXPECT_EQ(pngsIn(root()), std::vector<std::string>{"view_000.png"});
  EXPECT_EQ(calibration::readRobotPoseFile(pathOf("received.txt")).poses.size(), 1u);
  EXPECT_EQ(replies.waiting(kMonitor), 0u);
}

TEST_F(GuidedSession, ASecondSessionContinuesTheFirst) {
  start(3);
  camera.queue(boardImage());
  expectPoseReply(ask(pose(0.5)), Status::Ok, 1, 3);
  camera.queue(testing::blankImage());
  expectPoseReply(ask(pose(0.5)), Status::BoardNotFound, 1, 3);
  session.reset();
  start(3);
  camera.queue(boardImage(30));
  expectPoseReply(ask(pose(0.7)), Status::Ok, 2, 3);
  EXPECT_EQ(pngsIn(root()), (std::vector<std::string>{"view_000.png", "view_001.png"}));
  EXPECT_TRUE(fs::exists(pathOf("rejected/attempt_002.png")));
  EXPECT_EQ(calibration::readRobotPoseFile(pathOf("received.txt")).poses.back().view, "attempt_003");
  // Poses in another convention would make a file that is not one: refused.
  session.reset();
  EXPECT_THROW(GuidedViewRecorder(root(), core::Orientation::Quaternion), core::Error);
}

}  // namespace
}  // namespace binpick::cli
