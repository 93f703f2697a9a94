// The Aravis camera against Aravis's GigE Vision fake camera on the loopback interface: real
// GVCP control and GVSP streaming, with images we choose, and the faults a cell sees (lost
// packets, a camera that stops answering). Every test here binds UDP port 3956: ctest runs them
// one at a time (RESOURCE_LOCK gige_port_3956).
#include <gtest/gtest.h>

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "binpick/acquisition/aravis_camera.hpp"
#include "binpick/acquisition/fake_gige_camera.hpp"
#include "binpick/core/error.hpp"
#include "binpick/simulation/pattern_renderer.hpp"
#include "rendered_pile.hpp"
#include "thrown_message.hpp"

namespace binpick::acquisition {
namespace {

constexpr int kTimeoutMs = 2000;  // generous: loopback frames take milliseconds

FakeCameraParams fakeParams(int width, int height, bool sixteen_bit) {
  FakeCameraParams p;
  p.serial = "BINPICK-TEST";
  p.width = width;
  p.height = height;
  p.sixteen_bit = sixteen_bit;
  return p;
}

CameraParams cameraParams(const FakeGigECamera& fake, const std::string& pixel_format = "Mono8") {
  CameraParams p;
  p.id = fake.id();
  p.pixel_format = pixel_format;
  p.trigger = TriggerSource::Software;
  p.buffers = 4;
  return p;
}

// Ramps plus seeded noise: every byte differs between images, so a frame stitched from two
// images, or with stale bytes from an earlier frame, cannot pass for either.
cv::Mat syntheticImage(int width, int height, int type, uint64_t seed) {
  cv::Mat image(height, width, type);
  cv::RNG rng(seed);
  const double full = type == CV_8UC1 ? 255.0 : 65535.0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double ramp = full * (0.5 * x / width + 0.3 * y / height) + rng.uniform(0.0, 0.2 * full);
      if (type == CV_8UC1) {
        image.at<uint8_t>(y, x) = cv::saturate_cast<uint8_t>(ramp);
      } else {
        image.at<uint16_t>(y, x) = cv::saturate_cast<uint16_t>(ramp);
      }
    }
  }
  return image;
}

// Structured-light images (column Gray codes) of a slanted plane from the virtual cell's image
// formation. Tests make their images before opening the camera: under a slow runner (valgrind)
// a long pause between open() and the first frame can cost the heartbeat its control.
std::vector<cv::Mat> patternImages(int width, int height, int bit_depth, int count) {
  std::vector<simulation::PixelLighting> pixels(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      simulation::PixelLighting& p =
          pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
      p.projector_x = 0.9f * static_cast<float>(x) + 40.0f;
      p.projector_y = 0.7f * static_cast<float>(y) + 30.0f;
      p.blur_sigma = 0.6f;
      p.direct = 150.0f + 60.0f * static_cast<float>(x) / static_cast<float>(width);
      p.ambient = 6.0f;
      p.global = 3.0f;
    }
  }
  simulation::PhotometryParams photometry;
  photometry.bit_depth = bit_depth;
  photometry.seed = 5;
  io::PatternSetSpec spec;
  spec.row_codes = false;
  spec.phase_steps = 0;
  std::vector<cv::Mat> images = simulation::renderPatternImages(pixels, width, height, spec, photometry);
  images.resize(static_cast<std::size_t>(count));
  return images;
}

using testing::identical;

Frame triggerAndGrab(Camera& camera) {
  camera.trigger();
  return camera.grab(kTimeoutMs);
}

// Serves `image`, triggers one frame and checks that it arrives whole and byte for byte.
::testing::AssertionResult servedFrameArrives(FakeGigECamera& fake, Camera& camera, const cv::Mat& image) {
  fake.serve(image);
  const Frame frame = triggerAndGrab(camera);
  if (frame.status != FrameStatus::Ok) {
    return ::testing::AssertionFailure() << frameStatusName(frame.status) << ": " << frame.detail;
  }
  if (!identical(frame.image, image)) return ::testing::AssertionFailure() << "the frame differs from the image";
  return ::testing::AssertionSuccess();
}

std::string openError(Camera& camera) {
  return binpick::test::thrownMessage([&] { camera.open(); });
}

TEST(GigECamera, ServedEightBitFramesArriveByteIdentical) {
  std::vector<cv::Mat> images = patternImages(640, 512, 8, 2);
  images.push_back(syntheticImage(640, 512, CV_8UC1, 1));
  images.push_back(syntheticImage(640, 512, CV_8UC1, 2));
  FakeGigECamera fake(fakeParams(640, 512, false));
  const auto camera = makeAravisCamera(cameraParams(fake));
  camera->open();
  EXPECT_NE(camera->description().find("BINPICK-TEST"), std::string::npos) << camera->description();
  camera->start();
  uint64_t last_id = 0;
  for (const cv::Mat& image : images) {
    fake.serve(image);
    const Frame frame = triggerAndGrab(*camera);
    ASSERT_EQ(frame.status, FrameStatus::Ok) << frame.detail;
    EXPECT_TRUE(identical(frame.image, image));
    EXPECT_GT(frame.frame_id, last_id);
    EXPECT_GT(frame.system_time_ns, 0u);
    last_id = frame.frame_id;
  }
  EXPECT_EQ(camera->statistics().completed_frames, images.size());
  camera->stop();
  EXPECT_EQ(camera->statistics().completed_frames, images.size()) << "the last run's counters stay readable";
}

TEST(GigECamera, ServedSixteenBitFramesArriveByteIdentical) {
  std::vector<cv::Mat> images = patternImages(640, 512, 16, 2);
  images.push_back(syntheticImage(640, 512, CV_16UC1, 3));
  FakeGigECamera fake(fakeParams(640, 512, true));
  const auto camera = makeAravisCamera(cameraParams(fake, "Mono16"));
  camera->open();
  camera->start();
  for (const cv::Mat& image : images) {
    fake.serve(image);
    const Frame frame = triggerAndGrab(*camera);
    ASSERT_EQ(frame.status, FrameStatus::Ok) << frame.detail;
    ASSERT_EQ(frame.image.type(), CV_16UC1);
    EXPECT_TRUE(identical(frame.image, image));
  }
}

TEST(GigECamera, FullSizeFramesFollowTheVirtualProjector) {
  const std::vector<cv::Mat> images = patternImages(1280, 1024, 8, 3);
  FakeGigECamera fake(fakeParams(1280, 1024, false));
  const auto projector = makeVirtualProjector(fake, images);
  CameraParams params = cameraParams(fake);
  params.packet_size = 8192;
  const auto camera = makeAravisCamera(params);
  camera->open();
  camera->start();
  for (int k = 0; k < static_cast<int>(images.size()); ++k) {
    projector->showPattern(k);
    const Frame frame = triggerAndGrab(*camera);
    ASSERT_EQ(frame.status, FrameStatus::Ok) << "pattern " << k << ": " << frame.detail;
    EXPECT_TRUE(identical(frame.image, images[static_cast<std::size_t>(k)])) << "pattern " << k;
  }
  EXPECT_THROW(projector->showPattern(3), core::Error);
  EXPECT_NE(projector->description().find("3 images"), std::string::npos);
}

TEST(GigECamera, RegionOfInterestCutsTheSensorImage) {
  FakeGigECamera fake(fakeParams(640, 512, false));
  CameraParams params = cameraParams(fake);
  params.roi = cv::Rect(32, 16, 320, 240);
  const auto camera = makeAravisCamera(params);
  camera->open();
  camera->start();
  const cv::Mat image = syntheticImage(640, 512, CV_8UC1, 4);
  fake.serve(image);
  const Frame frame = triggerAndGrab(*camera);
  ASSERT_EQ(frame.status, FrameStatus::Ok) << frame.detail;
  EXPECT_TRUE(identical(frame.image, image(params.roi)));
}

TEST(GigECamera, NoTriggerMeansTimeoutThenTheCameraStillWorks) {
  FakeGigECamera fake(fakeParams(640, 512, false));
  const auto camera = makeAravisCamera(cameraParams(fake));
  camera->open();
  camera->start();
  const Frame none = camera->grab(200);
  EXPECT_EQ(none.status, FrameStatus::Timeout);
  EXPECT_TRUE(none.image.empty());
  EXPECT_NE(none.detail.find("200 ms"), std::string::npos) << none.detail;
  const cv::Mat image = syntheticImage(640, 512, CV_8UC1, 5);
  EXPECT_TRUE(servedFrameArrives(fake, *camera, image));
}

// Aravis 0.8's fake ignores resend requests, so a lost packet loses the frame: what matters is
// that no frame with a hole (or with bytes left from an earlier frame) is ever called Ok.
TEST(GigECamera, LostPacketsNeverGiveACorruptedOkFrame) {
  FakeGigECamera fake(fakeParams(640, 512, false));
  CameraParams params = cameraParams(fake);
  params.packet_size = 8192;  // ~41 packets a frame: at 2% loss about half the frames survive
  const auto camera = makeAravisCamera(params);
  camera->open();
  camera->start();
  fake.setPacketLoss(0.02, 7);
  int ok = 0, incomplete = 0;
  for (int i = 0; i < 20; ++i) {
    const cv::Mat image = syntheticImage(640, 512, CV_8UC1, 100 + static_cast<uint64_t>(i));
    fake.serve(image);
    const Frame frame = triggerAndGrab(*camera);
    if (frame.status == FrameStatus::Ok) {
      ++ok;
      EXPECT_TRUE(identical(frame.image, image)) << "frame " << i << " is Ok but differs from what was served";
    } else {
      EXPECT_TRUE(frame.status == FrameStatus::Incomplete || frame.status == FrameStatus::Timeout)
          << "frame " << i << ": " << frameStatusName(frame.status) << " " << frame.detail;
      EXPECT_TRUE(frame.image.empty());
      if (frame.status == FrameStatus::Incomplete) ++incomplete;
    }
  }
  EXPECT_GT(incomplete, 0);
  EXPECT_GT(ok, 0);
  const StreamStatistics stats = camera->statistics();
  EXPECT_GT(stats.missing_packets, 0u);
  EXPECT_EQ(stats.completed_frames, static_cast<uint64_t>(ok));

  fake.setPacketLoss(0.0);
  const cv::Mat image = syntheticImage(640, 512, CV_8UC1, 99);
  EXPECT_TRUE(servedFrameArrives(fake, *camera, image));
}

TEST(GigECamera, LostControlIsReportedAndReopeningRecovers) {
  FakeGigECamera fake(fakeParams(640, 512, false));
  const auto camera = makeAravisCamera(cameraParams(fake));
  camera->open();
  camera->start();
  fake.serve(syntheticImage(640, 512, CV_8UC1, 6));
  ASSERT_EQ(triggerAndGrab(*camera).status, FrameStatus::Ok);

  fake.suspend();
  // The heartbeat thread notices; grab reports it (within Aravis's heartbeat retries at worst).
  Frame lost;
  for (int i = 0; i < 40 && lost.status != FrameStatus::ConnectionLost; ++i) {
    camera->trigger();  // skipped once the loss is known: must not throw or block
    lost = camera->grab(250);
    EXPECT_TRUE(lost.status == FrameStatus::ConnectionLost || lost.status == FrameStatus::Timeout)
        << frameStatusName(lost.status) << " " << lost.detail;
  }
  EXPECT_EQ(lost.status, FrameStatus::ConnectionLost);
  EXPECT_TRUE(camera->connectionLost());
  camera->stop();  // must not wait on the vanished camera

  fake.resume();
  camera->open();
  EXPECT_FALSE(camera->connectionLost());
  camera->start();
  const cv::Mat image = syntheticImage(640, 512, CV_8UC1, 7);
  EXPECT_TRUE(servedFrameArrives(fake, *camera, image));
}

TEST(GigECamera, UnknownCameraIdIsNamedInTheError) {
  CameraParams params;
  params.id = "BINPICK-NO-SUCH-CAMERA";
  const auto camera = makeAravisCamera(params);
  const std::string error = openError(*camera);
  EXPECT_NE(error.find("BINPICK-NO-SUCH-CAMERA"), std::string::npos) << error;
  EXPECT_FALSE(camera->isOpen());
  EXPECT_EQ(camera->grab(10).status, FrameStatus::Failed);
  EXPECT_THROW(camera->start(), core::Error);
}

TEST(GigECamera, SettingsTheCameraRefusesAreNamed) {
  FakeGigECamera fake(fakeParams(640, 512, false));
  CameraParams format = cameraParams(fake, "Mono12");  // the fake has Mono8 and Mono16 only
  std::string error = openError(*makeAravisCamera(format));
  EXPECT_NE(error.find("pixel_format"), std::string::npos) << error;
  EXPECT_NE(error.find(fake.id()), std::string::npos) << error;

  CameraParams line = cameraParams(fake);
  line.trigger = TriggerSource::Hardware;  // the fake has no Line1
  error = openError(*makeAravisCamera(line));
  EXPECT_NE(error.find("hardware_trigger_line"), std::string::npos) << error;

  CameraParams gain = cameraParams(fake);
  gain.gain_db = 20.0;  // the fake's gain goes to 10
  error = openError(*makeAravisCamera(gain));
  EXPECT_NE(error.find("gain_db"), std::string::npos) << error;

  CameraParams exposure = cameraParams(fake);
  exposure.exposure_us = 5.0;  // the fake's shortest is 10 us
  error = openError(*makeAravisCamera(exposure));
  EXPECT_NE(error.find("exposure_us"), std::string::npos) << error;

  CameraParams roi = cameraParams(fake);
  roi.roi = cv::Rect(600, 0, 200, 100);  // past the sensor's right edge
  const auto camera = makeAravisCamera(roi);
  error = openError(*camera);
  EXPECT_NE(error.find("roi"), std::string::npos) << error;
  EXPECT_FALSE(camera->isOpen());
}

TEST(GigECamera, InvalidParamsAreRefusedBeforeAnyCameraIsTouched) {
  CameraParams buffers;
  buffers.buffers = 1;
  try {
    makeAravisCamera(buffers);
    ADD_FAILURE() << "no error";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("camera params.buffers"), std::string::npos) << e.what();
  }
  EXPECT_THROW(FakeGigECamera(fakeParams(0, 512, false)), core::Error);
}

TEST(FakeGigECamera, RefusesAWrongImageAndASecondServerOnThePort) {
  FakeGigECamera fake(fakeParams(640, 512, false));
  EXPECT_THROW(fake.serve(cv::Mat(512, 640, CV_16UC1, cv::Scalar(0))), core::Error);
  EXPECT_THROW(fake.serve(cv::Mat(100, 100, CV_8UC1, cv::Scalar(0))), core::Error);
  EXPECT_THROW(fake.setPacketLoss(1.5), core::Error);
  EXPECT_THROW(FakeGigECamera second(fakeParams(640, 512, false)), core::Error);
}

}  // namespace
}  // namespace binpick::acquisition
