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
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/pile.hpp"

namespace binpick::acquisition {
namespace {

struct Rendered {
  sim::PileParams params;
  sim::PileCapture pile;
  PatternSetSpec patterns;
};

// A quarter-resolution camera (320 x 256): small frames keep loopback streaming fast.
const Rendered& rendered() {
  static const Rendered r = [] {
    Rendered out;
    out.params.objects = 6;
    out.params.seed = 4;
    out.params.rig.camera = out.params.rig.camera.scaled(0.25);
    out.patterns.projector_width = out.params.rig.projector.width;
    out.patterns.projector_height = out.params.rig.projector.height;
    out.pile = sim::generatePileCapture(sim::makePart("clamp").mesh, out.params, out.patterns, {});
    return out;
  }();
  return r;
}

bool identical(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

TEST(LiveCapture, RecordsTheRenderedPatternsByteForByteAndReplaysAndReconstructsThem) {
  const Rendered& r = rendered();
  FakeCameraParams fake;
  fake.width = r.params.rig.camera.width;
  fake.height = r.params.rig.camera.height;
  FakeGigECamera server(fake);
  CameraParams camera_params;
  camera_params.id = server.id();
  const auto camera = makeAravisCamera(camera_params);
  const auto projector = makeVirtualProjector(server, r.pile.images);
  SequencerParams sequencer_params;
  sequencer_params.settle_us = 0;
  CaptureSequencer sequencer(*camera, *projector, sequencer_params);
  camera->open();
  camera->start();
  SequencerReport report;
  const Capture capture = sequencer.capture(r.patterns, &report);
  camera->stop();
  camera->close();

  ASSERT_EQ(capture.images.size(), r.pile.images.size());
  for (std::size_t k = 0; k < capture.images.size(); ++k) {
    EXPECT_TRUE(identical(capture.images[k], r.pile.images[k])) << "pattern " << k << " " << capture.metadata.patterns[k];
  }
  const std::string directory = (std::filesystem::temp_directory_path() / "binpick_live_capture_test").string();
  std::filesystem::remove_all(directory);
  writeCapture(directory, capture);
  ReplayParams replay;
  replay.path = directory;
  const Capture replayed = makeReplaySource(replay)->next();
  for (std::size_t k = 0; k < replayed.images.size(); ++k) EXPECT_TRUE(identical(replayed.images[k], r.pile.images[k]));
  const reconstruction::Reconstruction cloud = reconstruction::Reconstructor(r.pile.scene.rig).reconstruct(replayed);
  EXPECT_GT(cloud.validPoints(), cloud.cloud.size() / 4);
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace binpick::acquisition
