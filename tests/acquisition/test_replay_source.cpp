// Replay: recorded capture directories come back bit-identical, in name order, looping or ending
// with an error, and a recording that never finished is named instead of skipped.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "acquisition_test_dir.hpp"
#include "binpick/acquisition/capture_source.hpp"
#include "binpick/acquisition/sequencer.hpp"
#include "binpick/reconstruction/pattern_set.hpp"
#include "fake_camera.hpp"
#include "rendered_pile.hpp"
#include "thrown_message.hpp"

namespace binpick::acquisition {
namespace {

namespace fs = std::filesystem;
using testing::identical;
using testing::renderedPile;

class ReplaySource : public testing::TempDirTest {};

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A tiny capture (14 patterns of 16 x 12 pixels) whose images all hold `value`, and whose source
// says `name`: enough to tell captures apart.
io::Capture tinyCapture(const std::string& name, int value) {
  io::Capture capture;
  io::PatternSetSpec& spec = capture.metadata.pattern_set;
  spec.projector_width = 64;
  spec.projector_height = 32;
  spec.row_codes = false;
  spec.phase_steps = 0;
  capture.metadata.patterns = reconstruction::patternNames(spec);
  capture.metadata.source = name;
  capture.metadata.timestamp = io::utcTimestamp();
  capture.metadata.image_width = 16;
  capture.metadata.image_height = 12;
  for (std::size_t i = 0; i < capture.metadata.patterns.size(); ++i) {
    capture.images.emplace_back(12, 16, CV_8UC1, cv::Scalar(value));
  }
  return capture;
}

std::string nextError(CaptureSource& source) {
  return binpick::test::thrownMessage([&] { source.next(); });
}

std::string makeError(const ReplayParams& params) {
  return binpick::test::thrownMessage([&] { makeReplaySource(params); });
}

TEST_F(ReplaySource, RecordedCaptureReplaysBitIdentical) {
  // Record mode: the sequencer's capture written as it came from the camera.
  auto state = std::make_shared<testing::FakeRigState>();
  state->images = renderedPile().images;
  testing::FakeCamera camera(state);
  testing::FakeProjector projector(state);
  camera.open();
  camera.start();
  SequencerParams params;
  params.settle_us = 0;
  const io::Capture recorded = CaptureSequencer(camera, projector, params).capture(renderedPile().patterns);
  const std::string directory = pathOf("capture_0001");
  io::writeCapture(directory, recorded, 2);

  ReplayParams replay;
  replay.path = directory;
  replay.threads = 2;
  const auto source = makeReplaySource(replay);
  const io::Capture replayed = source->next();
  ASSERT_EQ(replayed.images.size(), recorded.images.size());
  for (std::size_t i = 0; i < replayed.images.size(); ++i) {
    EXPECT_TRUE(identical(replayed.images[i], renderedPile().images[i])) << "image " << i;
  }
  EXPECT_EQ(replayed.metadata.patterns, recorded.metadata.patterns);
  EXPECT_EQ(replayed.metadata.source, recorded.metadata.source);
  EXPECT_EQ(replayed.metadata.timestamp, recorded.metadata.timestamp);
  EXPECT_EQ(replayed.metadata.bit_depth, 8);
  // A single capture directory is a replay of one.
  EXPECT_EQ(nextError(*source), "replay: no more captures in " + directory);
}

TEST_F(ReplaySource, ReplaysADirectoryOfCapturesInNameOrderThenEnds) {
  io::writeCapture(pathOf("2024-01-02_b"), tinyCapture("b", 2));
  io::writeCapture(pathOf("2024-01-01_a"), tinyCapture("a", 1));
  io::writeCapture(pathOf("2024-01-03_c"), tinyCapture("c", 3));
  std::ofstream(pathOf("notes.txt")) << "cell 3, shift 2\n";  // files beside captures are ignored
  ReplayParams params;
  params.path = root();
  const auto source = makeReplaySource(params);
  EXPECT_EQ(source->next().metadata.source, "a");
  const io::Capture b = source->next();
  EXPECT_EQ(b.metadata.source, "b");
  EXPECT_EQ(b.images[5].at<uint8_t>(3, 4), 2);
  EXPECT_EQ(source->next().metadata.source, "c");
  EXPECT_EQ(nextError(*source), "replay: no more captures in " + root());
  EXPECT_EQ(nextError(*source), "replay: no more captures in " + root());  // and stays at the end
}

TEST_F(ReplaySource, LoopsWhenAsked) {
  io::writeCapture(pathOf("a"), tinyCapture("a", 1));
  io::writeCapture(pathOf("b"), tinyCapture("b", 2));
  ReplayParams params;
  params.path = root();
  params.loop = true;
  const auto source = makeReplaySource(params);
  std::string order;
  for (int i = 0; i < 5; ++i) order += source->next().metadata.source;
  EXPECT_EQ(order, "ababa");
}

TEST_F(ReplaySource, NamesAHalfWrittenCapture) {
  io::writeCapture(pathOf("a"), tinyCapture("a", 1));
  io::writeCapture(pathOf("c"), tinyCapture("c", 3));
  // What an interrupted writeCapture leaves: images, no capture.json.
  fs::create_directories(pathOf("b/images"));
  ReplayParams params;
  params.path = root();
  const std::string error = makeError(params);
  EXPECT_TRUE(contains(error, pathOf("b"))) << error;
  EXPECT_TRUE(contains(error, "no capture.json")) << error;
}

TEST_F(ReplaySource, ADamagedCaptureIsReportedAndTheReplayGoesOn) {
  io::writeCapture(pathOf("a"), tinyCapture("a", 1));
  io::writeCapture(pathOf("b"), tinyCapture("b", 2));
  io::writeCapture(pathOf("c"), tinyCapture("c", 3));
  fs::remove(pathOf("b/images/004_gray_col_01.png"));
  ReplayParams params;
  params.path = root();
  const auto source = makeReplaySource(params);
  EXPECT_EQ(source->next().metadata.source, "a");
  const std::string error = nextError(*source);
  EXPECT_TRUE(contains(error, "004_gray_col_01.png")) << error;
  EXPECT_EQ(source->next().metadata.source, "c");
}

TEST_F(ReplaySource, APathWithoutCapturesFailsEachCaptureUntilOneIsRecorded) {
  // A cell installed but not yet recorded starts; each capture says why there is nothing to replay.
  ReplayParams missing;
  missing.path = pathOf("nowhere");
  const auto from_missing = makeReplaySource(missing);
  EXPECT_EQ(nextError(*from_missing), "replay: " + pathOf("nowhere") + " is not a directory");
  ReplayParams empty;
  empty.path = root();
  const auto from_empty = makeReplaySource(empty);
  EXPECT_TRUE(contains(nextError(*from_empty), root() + " holds no capture")) << nextError(*from_empty);
  EXPECT_TRUE(contains(from_empty->description(), "no capture yet")) << from_empty->description();
  // A recording copied in later is found at the next capture, without a restart.
  io::writeCapture(pathOf("a"), tinyCapture("a", 1));
  EXPECT_EQ(from_empty->next().metadata.source, "a");
}

TEST_F(ReplaySource, ParamsAreCheckedNamingTheField) {
  ReplayParams no_path;
  EXPECT_TRUE(contains(makeError(no_path), "replay params.path")) << makeError(no_path);
  ReplayParams threads;
  threads.path = root();
  threads.threads = -1;
  EXPECT_TRUE(contains(makeError(threads), "replay params.threads")) << makeError(threads);
}

}  // namespace
}  // namespace binpick::acquisition
