// The capture sequencer against an in-memory camera: one whole frame per pattern, in order, with
// bounded retries for lost frames and an error that names the pattern when they do not suffice.
#include <gtest/gtest.h>

#include <algorithm>

#include <string>

#include "binpick/acquisition/sequencer.hpp"
#include "binpick/reconstruction/pattern_set.hpp"
#include "fake_camera.hpp"
#include "rendered_pile.hpp"
#include "thrown_message.hpp"

namespace binpick::acquisition {
namespace {

using testing::FakeCamera;
using testing::FakeProjector;
using testing::FakeRigState;
using testing::identical;
using testing::renderedPile;

// A fake rig serving the rendered pile, opened and streaming, and fast sequencer params.
struct Rig {
  std::shared_ptr<FakeRigState> state = std::make_shared<FakeRigState>();
  FakeCamera camera{state};
  FakeProjector projector{state};
  SequencerParams params;

  Rig() {
    state->images = renderedPile().images;
    params.settle_us = 0;
    camera.open();
    camera.start();
  }
  io::Capture capture(SequencerReport* report = nullptr) {
    return CaptureSequencer(camera, projector, params).capture(renderedPile().patterns, report);
  }
};

std::string captureError(Rig& rig, bool* connection_lost = nullptr) {
  try {
    rig.capture();
  } catch (const CaptureError& e) {
    if (connection_lost != nullptr) *connection_lost = e.connectionLost();
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string validationError(const SequencerParams& params) {
  return binpick::test::thrownMessage([&] { params.validate(); });
}

TEST(SequencerParams, DefaultsAreValid) { EXPECT_EQ(validationError(SequencerParams{}), ""); }

TEST(SequencerParams, RefusesNonsenseNamingTheField) {
  SequencerParams settle;
  settle.settle_us = -1;
  EXPECT_TRUE(contains(validationError(settle), "sequencer params.settle_us"));
  SequencerParams timeout;
  timeout.frame_timeout_ms = 0;
  EXPECT_TRUE(contains(validationError(timeout), "sequencer params.frame_timeout_ms"));
  SequencerParams retries;
  retries.max_retries = -1;
  EXPECT_TRUE(contains(validationError(retries), "sequencer params.max_retries"));
}

TEST(CaptureSequencer, RefusesInvalidParams) {
  Rig rig;
  rig.params.max_retries = -3;
  EXPECT_THROW(CaptureSequencer(rig.camera, rig.projector, rig.params), core::Error);
}

TEST(CaptureSequencer, CapturesEveryPatternAsRendered) {
  Rig rig;
  SequencerReport report;
  const io::Capture capture = rig.capture(&report);
  const auto& rendered = renderedPile();
  ASSERT_EQ(capture.images.size(), rendered.images.size());
  for (std::size_t i = 0; i < capture.images.size(); ++i) {
    EXPECT_TRUE(identical(capture.images[i], rendered.images[i])) << "image " << i;
  }
  // One pulse and one trigger per pattern, in the pattern set's order.
  ASSERT_EQ(rig.state->shown_log.size(), rendered.images.size());
  for (std::size_t i = 0; i < rig.state->shown_log.size(); ++i) EXPECT_EQ(rig.state->shown_log[i], static_cast<int>(i));
  EXPECT_EQ(rig.state->triggers, static_cast<int>(rendered.images.size()));
  EXPECT_EQ(report.retries, 0);
  EXPECT_TRUE(report.retry_reasons.empty());
  EXPECT_GE(report.milliseconds, 0.0);

  const io::CaptureMetadata& m = capture.metadata;
  EXPECT_EQ(m.image_width, rendered.images[0].cols);
  EXPECT_EQ(m.image_height, rendered.images[0].rows);
  EXPECT_EQ(m.bit_depth, 8);
  EXPECT_EQ(m.source, "Fake Vision FV-1 FAKE-0001");
  EXPECT_FALSE(m.timestamp.empty());
  EXPECT_EQ(m.patterns, reconstruction::patternNames(rendered.patterns));
  ASSERT_EQ(m.frame_times_ms.size(), m.patterns.size());  // every image time-stamped, in order
  EXPECT_TRUE(std::is_sorted(m.frame_times_ms.begin(), m.frame_times_ms.end()));
  EXPECT_EQ(m.pattern_set.projector_width, rendered.patterns.projector_width);
  EXPECT_EQ(m.pattern_set.projector_height, rendered.patterns.projector_height);
  EXPECT_EQ(m.pattern_set.row_codes, rendered.patterns.row_codes);
  EXPECT_EQ(m.pattern_set.phase_steps, rendered.patterns.phase_steps);
}

TEST(CaptureSequencer, SixteenBitFramesMakeASixteenBitCapture) {
  Rig rig;
  for (cv::Mat& image : rig.state->images) image.convertTo(image, CV_16UC1, 257.0);
  const io::Capture capture = rig.capture();
  EXPECT_EQ(capture.metadata.bit_depth, 16);
  EXPECT_TRUE(identical(capture.images.back(), rig.state->images.back()));
}

TEST(CaptureSequencer, CameraOnlyLeavesTriggeringToTheProjector) {
  Rig rig;
  rig.state->hardware_trigger = true;
  rig.params.order = TriggerOrder::CameraOnly;
  const io::Capture capture = rig.capture();
  EXPECT_EQ(rig.state->triggers, 0);
  EXPECT_TRUE(identical(capture.images[7], renderedPile().images[7]));
}

TEST(CaptureSequencer, RetriesALostFrameAndStillCompletes) {
  Rig rig;
  rig.state->frame_faults[5] = FrameStatus::Timeout;
  SequencerReport report;
  const io::Capture capture = rig.capture(&report);
  EXPECT_EQ(report.retries, 1);
  ASSERT_EQ(report.retry_reasons.size(), 1u);
  const std::string name = reconstruction::patternNames(renderedPile().patterns)[5];
  EXPECT_EQ(report.retry_reasons[0], "pattern 5 (" + name + "): timeout (scripted)");
  // The retry took the same pattern (the projector held it) and nothing shifted after it.
  ASSERT_EQ(capture.images.size(), renderedPile().images.size());
  for (std::size_t i = 0; i < capture.images.size(); ++i) {
    EXPECT_TRUE(identical(capture.images[i], renderedPile().images[i])) << "image " << i;
  }
  EXPECT_EQ(rig.state->shown_log.size(), renderedPile().images.size());
}

TEST(CaptureSequencer, RetriesAnIncompleteFrame) {
  Rig rig;
  rig.state->frame_faults[0] = FrameStatus::Incomplete;
  rig.state->frame_faults[9] = FrameStatus::Incomplete;
  SequencerReport report;
  rig.capture(&report);
  EXPECT_EQ(report.retries, 2);
  ASSERT_EQ(report.retry_reasons.size(), 2u);
  EXPECT_TRUE(contains(report.retry_reasons[0], "pattern 0 (white): incomplete"));
  // Frame 9 is pattern 8: frame 0 was retried.
  EXPECT_TRUE(contains(report.retry_reasons[1], "pattern 8 ("));
}

TEST(CaptureSequencer, AFrameLostBeyondTheRetriesNamesThePattern) {
  Rig rig;
  rig.params.max_retries = 2;
  rig.state->failing_pattern = 12;
  bool lost = true;
  const std::string error = captureError(rig, &lost);
  EXPECT_TRUE(contains(error, "pattern 12 (gray_col_05)")) << error;
  EXPECT_TRUE(contains(error, "3 triggers")) << error;
  EXPECT_TRUE(contains(error, "timeout")) << error;
  EXPECT_FALSE(lost);
  EXPECT_EQ(rig.state->triggers, 12 + 3);  // one per earlier pattern, three for pattern 12
}

TEST(CaptureSequencer, NoRetriesMeansTheFirstLostFrameFails) {
  Rig rig;
  rig.params.max_retries = 0;
  rig.state->frame_faults[3] = FrameStatus::Failed;
  const std::string error = captureError(rig);
  EXPECT_TRUE(contains(error, "pattern 3 (gray_col_00_inv)")) << error;
  EXPECT_TRUE(contains(error, "failed (scripted)")) << error;
}

TEST(CaptureSequencer, ALostConnectionFailsAtOnceWithoutRetries) {
  Rig rig;
  rig.state->lose_connection_at = 4;
  bool lost = false;
  const std::string error = captureError(rig, &lost);
  EXPECT_TRUE(lost);
  EXPECT_TRUE(contains(error, "pattern 4 (")) << error;
  EXPECT_TRUE(contains(error, "connection lost")) << error;
  EXPECT_EQ(rig.state->triggers, 5);
}

// A projector as the hardware is: each pulse shows the next pattern of its preloaded sequence,
// whatever the software means by it, and the sequence wraps after its last pattern.
class SequenceProjector : public ProjectorTrigger {
 public:
  SequenceProjector(std::shared_ptr<FakeRigState> state, std::size_t sequence_length)
      : state_(std::move(state)), sequence_length_(sequence_length) {}
  void showPattern(int /*index*/) override {
    state_->shown = static_cast<int>(pulses_++ % sequence_length_);
    state_->shown_log.push_back(state_->shown);
  }
  std::string description() const override { return "pulse-advanced projector"; }

 private:
  std::shared_ptr<FakeRigState> state_;
  std::size_t sequence_length_;
  std::size_t pulses_ = 0;
};

TEST(CaptureSequencer, AfterAnAbortedCaptureTheProjectorIsBroughtBackToItsFirstPattern) {
  Rig rig;
  const auto& rendered = renderedPile();
  SequenceProjector projector(rig.state, rendered.images.size());
  CaptureSequencer sequencer(rig.camera, projector, rig.params);
  rig.state->failing_pattern = 7;  // the capture stops there, the projector showing pattern 7
  EXPECT_THROW(sequencer.capture(rendered.patterns), CaptureError);

  rig.state->failing_pattern = -1;
  const io::Capture capture = sequencer.capture(rendered.patterns);
  ASSERT_EQ(capture.images.size(), rendered.images.size());
  for (std::size_t i = 0; i < capture.images.size(); ++i) {
    EXPECT_TRUE(identical(capture.images[i], rendered.images[i])) << "image " << i;
  }
  // 8 pulses of the stopped capture, the rest of the sequence, then the whole sequence again.
  EXPECT_EQ(rig.state->shown_log.size(), 2 * rendered.images.size());
}

// The same projector, and the cycle's deadline passing while it shows pattern `cancel_at`.
class DeadlineProjector : public SequenceProjector {
 public:
  DeadlineProjector(std::shared_ptr<FakeRigState> state, std::size_t sequence_length, int cancel_at,
                    core::CancelFlag& cancel)
      : SequenceProjector(std::move(state), sequence_length), cancel_at_(cancel_at), cancel_(cancel) {}
  void showPattern(int index) override {
    SequenceProjector::showPattern(index);
    if (pulses_++ == cancel_at_) cancel_.cancel();
  }

 private:
  int cancel_at_;
  int pulses_ = 0;
  core::CancelFlag& cancel_;
};

// A capture under way when its deadline passes (or the service stops) ends before the next
// pattern, and the next capture first brings the projector back to its first pattern.
TEST(CaptureSequencer, ACancelledCaptureStopsBeforeTheNextPatternAndTheNextOneResynchronises) {
  Rig rig;
  const auto& rendered = renderedPile();
  core::CancelFlag cancel;
  DeadlineProjector projector(rig.state, rendered.images.size(), 5, cancel);
  CaptureSequencer sequencer(rig.camera, projector, rig.params);
  EXPECT_THROW(sequencer.capture(rendered.patterns, nullptr, &cancel), core::Cancelled);
  EXPECT_EQ(rig.state->shown_log.size(), 6u) << "patterns shown before the capture stopped";

  const io::Capture capture = sequencer.capture(rendered.patterns);
  ASSERT_EQ(capture.images.size(), rendered.images.size());
  for (std::size_t i = 0; i < capture.images.size(); ++i) {
    EXPECT_TRUE(identical(capture.images[i], rendered.images[i])) << "image " << i;
  }
}

TEST(CaptureSequencer, RefusesAFrameOfAnotherSize) {
  Rig rig;
  rig.state->images[3] = cv::Mat(80, 100, CV_8UC1, cv::Scalar(7));
  const std::string error = captureError(rig);
  EXPECT_TRUE(contains(error, "pattern 3 (")) << error;
  EXPECT_TRUE(contains(error, "100x80")) << error;
}

TEST(CaptureSequencer, RefusesColourFrames) {
  Rig rig;
  rig.state->images[0] = cv::Mat(rig.state->images[0].size(), CV_8UC3, cv::Scalar(1, 2, 3));
  const std::string error = captureError(rig);
  EXPECT_TRUE(contains(error, "pattern 0 (white)")) << error;
  EXPECT_TRUE(contains(error, "8- or 16-bit grey")) << error;
}

}  // namespace
}  // namespace binpick::acquisition
