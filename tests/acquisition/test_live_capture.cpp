// The whole live path against a real GigE Vision peer on loopback: the virtual projector shows
// each rendered pattern on Aravis's fake camera, the sequencer triggers and grabs it through
// GigE Vision control and streaming, the capture is recorded, replayed and reconstructed.
#include <gtest/gtest.h>

#include <filesystem>

#include "binpick/acquisition/aravis_camera.hpp"
#include "binpick/acquisition/capture_source.hpp"
#include "binpick/acquisition/fake_gige_camera.hpp"
#include "binpick/acquisition/sequencer.hpp"
#include "binpick/reconstruction/reconstruction.hpp"
#include "rendered_pile.hpp"

namespace binpick::acquisition {
namespace {

using testing::identical;
using testing::renderedPile;

TEST(LiveCapture, RecordsTheRenderedPatternsByteForByteAndReplaysAndReconstructsThem) {
  const testing::RenderedPile& r = renderedPile();
  FakeCameraParams fake;
  fake.width = r.rig.camera.width;
  fake.height = r.rig.camera.height;
  FakeGigECamera server(fake);
  CameraParams camera_params;
  camera_params.id = server.id();
  const auto camera = makeAravisCamera(camera_params);
  const auto projector = makeVirtualProjector(server, r.images);
  SequencerParams sequencer_params;
  sequencer_params.settle_us = 0;
  CaptureSequencer sequencer(*camera, *projector, sequencer_params);
  camera->open();
  camera->start();
  SequencerReport report;
  const io::Capture capture = sequencer.capture(r.patterns, &report);
  camera->stop();
  camera->close();

  ASSERT_EQ(capture.images.size(), r.images.size());
  for (std::size_t k = 0; k < capture.images.size(); ++k) {
    EXPECT_TRUE(identical(capture.images[k], r.images[k])) << "pattern " << k << " " << capture.metadata.patterns[k];
  }
  const std::string directory = (std::filesystem::temp_directory_path() / "binpick_live_capture_test").string();
  std::filesystem::remove_all(directory);
  io::writeCapture(directory, capture);
  ReplayParams replay;
  replay.path = directory;
  const io::Capture replayed = makeReplaySource(replay)->next();
  for (std::size_t k = 0; k < replayed.images.size(); ++k) EXPECT_TRUE(identical(replayed.images[k], r.images[k]));
  const reconstruction::Reconstruction cloud = reconstruction::Reconstructor(r.rig).reconstruct(replayed);
  EXPECT_GT(cloud.validPoints(), cloud.cloud.size() / 4);
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace binpick::acquisition
