// Captures the decoder must refuse, each with a message that says what is wrong.
#include <gtest/gtest.h>

#include <string>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "binpick/core/error.hpp"
#include "binpick/reconstruction/decoder.hpp"
#include "thrown_message.hpp"
#include "virtual_capture.hpp"

namespace binpick::reconstruction {
namespace {

io::Capture smallCapture() {
  testing::CaptureOptions options;
  options.camera_scale = 0.5;
  return testing::deepCopy(testing::virtualCapture(options).capture);
}

// Runs the decoder and returns its error message ("" when it did not throw).
std::string decodeError(const io::Capture& capture, const DecodeParams& params = {}) {
  return binpick::test::thrownMessage([&] { decodeCapture(capture, params); });
}

constexpr int kGrayCol05 = 12;  // white, black, then gray_col_00 ... (pattern, inverse) pairs

TEST(DecoderErrors, RefusesAPatternSetThatDoesNotMatchTheImages) {
  io::Capture capture = smallCapture();
  capture.metadata.pattern_set.phase_steps = 3;
  const std::string message = decodeError(capture);
  EXPECT_NE(message.find("'phase_col_3') is not part of the pattern set"), std::string::npos) << message;
}

TEST(DecoderErrors, RefusesNamesOfNoPatternAndPatternsListedTwice) {
  io::Capture unknown = smallCapture();
  unknown.metadata.patterns[4] = "gray_col_1";
  EXPECT_NE(decodeError(unknown).find("image 4 ('gray_col_1') is no pattern name"), std::string::npos)
      << decodeError(unknown);
  io::Capture twice = smallCapture();
  twice.metadata.patterns[3] = twice.metadata.patterns[2];
  EXPECT_NE(decodeError(twice).find("is listed twice"), std::string::npos) << decodeError(twice);
  io::Capture missing = smallCapture();
  missing.metadata.patterns.erase(missing.metadata.patterns.begin() + kGrayCol05);
  missing.images.erase(missing.images.begin() + kGrayCol05);
  EXPECT_NE(decodeError(missing).find("gray_col_05 is missing"), std::string::npos) << decodeError(missing);
}

TEST(DecoderErrors, RefusesAMissingImage) {
  io::Capture capture = smallCapture();
  capture.images.pop_back();
  EXPECT_NE(decodeError(capture).find("images for"), std::string::npos);
}

TEST(DecoderErrors, RefusesImagesOfMixedSizesOrTypes) {
  io::Capture resized = smallCapture();
  cv::resize(resized.images[5], resized.images[5], cv::Size(100, 80));
  EXPECT_NE(decodeError(resized).find("image 5 (gray_col_01_inv) is 100x80"), std::string::npos);
  io::Capture retyped = smallCapture();
  retyped.images[7].convertTo(retyped.images[7], CV_16U);
  EXPECT_NE(decodeError(retyped).find("image 7 (gray_col_02_inv) is not a single-channel 8-bit"), std::string::npos);
}

TEST(DecoderErrors, RefusesACaptureWithoutColumnCodes) {
  io::Capture capture = smallCapture();
  capture.metadata.pattern_set.column_codes = false;
  capture.metadata.patterns.clear();  // whatever the names, the set itself is refused first
  EXPECT_FALSE(decodeError(capture).empty());
}

TEST(DecoderErrors, RefusesACaptureTakenWithTheProjectorOff) {
  io::Capture capture = smallCapture();
  for (cv::Mat& image : capture.images) capture.images[1].copyTo(image);  // everything black
  EXPECT_NE(decodeError(capture).find("projector did not light the scene"), std::string::npos);
}

TEST(DecoderErrors, RefusesAnOverexposedCapture) {
  io::Capture capture = smallCapture();
  for (cv::Mat& image : capture.images) image.convertTo(image, -1, 20.0);  // saturates
  EXPECT_NE(decodeError(capture).find("saturated on"), std::string::npos);
}

TEST(DecoderErrors, NamesTheFrameThatCameOutBlack) {
  io::Capture capture = smallCapture();
  capture.images[1].copyTo(capture.images[kGrayCol05]);
  const std::string message = decodeError(capture);
  EXPECT_NE(message.find("12 (gray_col_05)"), std::string::npos) << message;
  EXPECT_NE(message.find("a frame is missing, black or out of order"), std::string::npos);
}

TEST(DecoderErrors, NoticesFramesOutOfOrder) {
  io::Capture capture = smallCapture();
  std::swap(capture.images[kGrayCol05], capture.images[kGrayCol05 + 2]);  // col_05 <-> col_06
  EXPECT_NE(decodeError(capture).find("out of order"), std::string::npos);
  io::Capture phase = smallCapture();
  const int first_phase = 2 + 2 * 11;  // after the 11 column bits
  phase.images[1].copyTo(phase.images[first_phase + 1]);
  EXPECT_NE(decodeError(phase).find("phase image 25 (phase_col_1)"), std::string::npos);
}

TEST(DecoderErrors, RefusesParamsNamingTheField) {
  DecodeParams params;
  params.bit_margin = 1.5;
  EXPECT_NE(decodeError(smallCapture(), params).find("decode params.bit_margin must be in [0, 1)"), std::string::npos);
  DecodeParams unwrappable;
  unwrappable.max_code_run_with_phase = 16;
  EXPECT_NE(decodeError(smallCapture(), unwrappable).find("too short to unwrap"), std::string::npos);
}

}  // namespace
}  // namespace binpick::reconstruction
