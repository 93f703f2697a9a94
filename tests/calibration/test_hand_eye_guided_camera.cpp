// The guided session's cameras: a views directory replayed in name order, and the live camera
// reopened after every failed frame so that a late frame never stands for the next view.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>

#include "binpick/io/image_file.hpp"
#include "fake_camera.hpp"
#include "hand_eye_guided_camera.hpp"
#include "temp_directory_test.hpp"
#include "thrown_message.hpp"

namespace binpick::cli {
namespace {

namespace fs = std::filesystem;
using acquisition::FrameStatus;
using acquisition::testing::FakeCamera;
using acquisition::testing::FakeRigState;

class ReplayCamera : public test::TempDirectoryTest {
 protected:
  void write(const std::string& name, int grey) {
    fs::create_directories(fs::path(pathOf(name)).parent_path());
    io::writeImageFile(pathOf(name), cv::Mat(4, 6, CV_8UC1, cv::Scalar(grey)));
  }
};

TEST_F(ReplayCamera, ServesTheDirectorysImagesInNameOrderThenFails) {
  write("view_10.png", 30);
  write("view_02.png", 20);
  write("a.png", 10);
  write("rejected/attempt_001.png", 99);  // not the directory's own
  std::ofstream(pathOf("poses.txt")) << "orientation: quaternion\n";
  const std::unique_ptr<ViewCamera> camera = makeReplayViewCamera(root());
  for (int grey : {10, 20, 30}) EXPECT_EQ(camera->grab().at<uint8_t>(0, 0), grey);
  EXPECT_TRUE(test::throwsNaming([&] { camera->grab(); }, "all 3 images"));
  EXPECT_TRUE(test::throwsNaming([&] { camera->grab(); }, "all 3 images"));  // and stays so
}

TEST_F(ReplayCamera, ADirectoryWithoutImagesIsRefused) {
  EXPECT_TRUE(test::throwsNaming([&] { makeReplayViewCamera(root()); }, "no PNG images"));
  EXPECT_THROW(makeReplayViewCamera(pathOf("missing")), core::Error);
}

struct LiveCamera : ::testing::Test {
  LiveCamera() {
    state->images = {cv::Mat(4, 6, CV_8UC1, cv::Scalar(77))};
    state->shown = 0;  // no projector here: the camera sees the board as it is
  }
  std::shared_ptr<FakeRigState> state = std::make_shared<FakeRigState>();
  std::unique_ptr<ViewCamera> camera = makeLiveViewCamera(std::make_unique<FakeCamera>(state), 500);
};

TEST_F(LiveCamera, OpensOnceAndTriggersOneFramePerView) {
  for (int i = 0; i < 3; ++i) EXPECT_EQ(camera->grab().at<uint8_t>(0, 0), 77);
  EXPECT_EQ(state->opens, 1);
  EXPECT_EQ(state->triggers, 3);
}

TEST_F(LiveCamera, AFailedFrameClosesTheCameraAndTheNextViewReopensIt) {
  state->frame_faults[1] = FrameStatus::Incomplete;
  camera->grab();
  EXPECT_TRUE(test::throwsNaming([&] { camera->grab(); }, "incomplete"));
  EXPECT_FALSE(state->open);  // nothing left over to pass for the next view's frame
  EXPECT_EQ(camera->grab().at<uint8_t>(0, 0), 77);
  EXPECT_EQ(state->opens, 2);
}

TEST_F(LiveCamera, ALostCameraIsReopenedAndOneThatWillNotOpenIsRetried) {
  state->lose_connection_at = 0;
  EXPECT_THROW(camera->grab(), core::Error);
  state->lose_connection_at = std::numeric_limits<uint64_t>::max();
  state->failing_opens = 1;
  EXPECT_TRUE(test::throwsNaming([&] { camera->grab(); }, "not found"));
  EXPECT_EQ(camera->grab().at<uint8_t>(0, 0), 77);
  EXPECT_EQ(state->open_attempts, 3);
}

}  // namespace
}  // namespace binpick::cli
