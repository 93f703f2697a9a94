// Captures of other rigs' pattern sequences: any order, no white and black, no inverses, a code
// covering several projector pixels. Each is made from a virtual-cell capture and decoded against
// the decode of the capture as binpick takes it, or against the truth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/reconstruction/decoder.hpp"
#include "binpick/reconstruction/rig_sequence.hpp"
#include "thrown_message.hpp"
#include "virtual_capture.hpp"

namespace binpick::reconstruction {
namespace {

using testing::CaptureOptions;
using testing::virtualCapture;

CaptureOptions smallOptions() {
  CaptureOptions options;
  options.camera_scale = 0.5;
  return options;
}

const io::Capture& ours() { return virtualCapture(smallOptions()).capture; }

// The capture's images and names in the order of `order` (indices into it).
io::Capture reordered(const io::Capture& capture, const std::vector<std::size_t>& order) {
  io::Capture result;
  result.metadata = capture.metadata;
  result.metadata.patterns.clear();
  result.metadata.images.clear();
  for (const std::size_t i : order) {
    result.images.push_back(capture.images[i]);
    result.metadata.patterns.push_back(capture.metadata.patterns[i]);
  }
  return result;
}

// The capture without the patterns whose name `drop` accepts.
io::Capture without(const io::Capture& capture, const std::function<bool(const std::string&)>& drop) {
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < capture.images.size(); ++i) {
    if (!drop(capture.metadata.patterns[i])) kept.push_back(i);
  }
  return reordered(capture, kept);
}

bool endsWith(const std::string& text, const std::string& tail) {
  return text.size() >= tail.size() && text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}
bool isWhiteOrBlack(const std::string& name) { return name == "white" || name == "black"; }
bool isInverse(const std::string& name) { return endsWith(name, "_inv"); }

bool valid(const DecodedCapture& decoded, int pixel) {
  return decoded.status.ptr<uint8_t>(0)[pixel] == static_cast<uint8_t>(PixelStatus::Valid);
}

// How `other` decodes compared with `reference`: its valid pixels as a share of the reference's,
// and the share of the pixels valid in both whose column agrees within `tolerance` pixels.
struct Agreement {
  double coverage = 0.0;
  double agreeing = 0.0;
};
Agreement compare(const DecodedCapture& reference, const DecodedCapture& other, double tolerance) {
  int reference_valid = 0, other_valid = 0, both = 0, agree = 0;
  for (int i = 0; i < static_cast<int>(reference.column.total()); ++i) {
    reference_valid += valid(reference, i) ? 1 : 0;
    other_valid += valid(other, i) ? 1 : 0;
    if (!valid(reference, i) || !valid(other, i)) continue;
    ++both;
    agree += std::fabs(reference.column.ptr<float>(0)[i] - other.column.ptr<float>(0)[i]) <= tolerance ? 1 : 0;
  }
  return {static_cast<double>(other_valid) / reference_valid, static_cast<double>(agree) / std::max(both, 1)};
}

bool identical(const cv::Mat& a, const cv::Mat& b) {
  if (a.empty() || b.empty()) return a.empty() == b.empty();
  cv::Mat differs;
  cv::compare(a, b, differs, cv::CMP_NE);  // NaN != NaN: NaN pixels compared through status
  cv::Mat both_nan = (a != a) & (b != b);
  return cv::countNonZero(differs & ~both_nan) == 0;
}

TEST(RigSequences, PatternsInAnyOrderDecodeAsInOurs) {
  const io::Capture& capture = ours();
  const DecodedCapture reference = decodeCapture(capture);
  // OpenCV's GrayCodePattern order: the Gray pairs of the columns, then of the rows, then white
  // and black; the phase images stay after each axis's bits. Then a seeded shuffle.
  std::vector<std::size_t> opencv_order;
  for (std::size_t i = 2; i < capture.images.size(); ++i) opencv_order.push_back(i);
  opencv_order.insert(opencv_order.end(), {0, 1});
  std::vector<std::size_t> shuffled(capture.images.size());
  for (std::size_t i = 0; i < shuffled.size(); ++i) shuffled[i] = i;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(11));
  for (const auto& order : {opencv_order, shuffled}) {
    const DecodedCapture decoded = decodeCapture(reordered(capture, order));
    EXPECT_TRUE(identical(decoded.status, reference.status));
    EXPECT_TRUE(identical(decoded.column, reference.column));
    EXPECT_TRUE(identical(decoded.row, reference.row));
  }
}

TEST(RigSequences, WithoutWhiteAndBlackTheCoarsestBitAndItsInverseStandIn) {
  const DecodedCapture reference = decodeCapture(ours());
  const Agreement agreement = compare(reference, decodeCapture(without(ours(), isWhiteOrBlack)), 0.5);
  EXPECT_GT(agreement.coverage, 0.95);
  EXPECT_GT(agreement.agreeing, 0.995);
}

TEST(RigSequences, WithoutInversesWhiteAndBlackSetEachBitsThreshold) {
  const DecodedCapture reference = decodeCapture(ours());
  const Agreement agreement = compare(reference, decodeCapture(without(ours(), isInverse)), 0.5);
  EXPECT_GT(agreement.coverage, 0.85);
  EXPECT_GT(agreement.agreeing, 0.99);
}

TEST(RigSequences, WithNeitherThePhaseImagesSetWhiteAndBlack) {
  const DecodedCapture reference = decodeCapture(ours());
  const auto neither = [](const std::string& name) { return isWhiteOrBlack(name) || isInverse(name); };
  const Agreement agreement = compare(reference, decodeCapture(without(ours(), neither)), 0.5);
  EXPECT_GT(agreement.coverage, 0.8);
  EXPECT_GT(agreement.agreeing, 0.99);
}

TEST(RigSequences, NothingToMakeWhiteAndBlackFromIsNamed) {
  CaptureOptions gray_only = smallOptions();
  gray_only.phase_steps = 0;
  const auto neither = [](const std::string& name) { return isWhiteOrBlack(name) || isInverse(name); };
  const io::Capture capture = without(virtualCapture(gray_only).capture, neither);
  const std::string message = binpick::test::thrownMessage([&] { decodeCapture(capture); });
  EXPECT_NE(message.find("no white and black images"), std::string::npos) << message;
}

// A rig whose patterns code blocks of 2 x 2 projector pixels: the coordinates come out in the
// projector's pixels, as its calibration has them.
TEST(RigSequences, ACodeStepOfTwoDecodesToProjectorPixels) {
  for (const int phase_steps : {4, 0}) {
    CaptureOptions options = smallOptions();
    options.code_step = 2;
    options.phase_steps = phase_steps;
    const testing::VirtualCapture& v = virtualCapture(options);
    const DecodedCapture decoded = decodeCapture(v.capture);
    std::vector<double> errors;
    int measurable = 0;
    for (int i = 0; i < static_cast<int>(v.pixelCount()); ++i) {
      measurable += v.measurable(static_cast<std::size_t>(i)) ? 1 : 0;
      if (!valid(decoded, i)) continue;
      errors.push_back(
          std::fabs(decoded.column.ptr<float>(0)[i] - v.trueProjectorPixel(static_cast<std::size_t>(i)).x()));
    }
    ASSERT_GT(errors.size(), 0.8 * measurable) << phase_steps << " phase steps";
    std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
    // Gray code alone quantises to a code: 2 pixels wide, at most 1 pixel from its centre.
    EXPECT_LT(errors[errors.size() / 2], phase_steps > 0 ? 0.3 : 0.75) << phase_steps << " phase steps";
  }
}

// Decoded columns against the truth: the share of the measurable pixels decoded, the median
// error and the share of decoded pixels more than `far` projector pixels off.
struct TruthAgreement {
  double coverage = 0.0;
  double median_px = 0.0;
  double far_share = 0.0;
};
TruthAgreement againstTruth(const testing::VirtualCapture& v, const DecodedCapture& decoded, double far) {
  std::vector<double> errors;
  int measurable = 0, far_off = 0;
  for (int i = 0; i < static_cast<int>(v.pixelCount()); ++i) {
    measurable += v.measurable(static_cast<std::size_t>(i)) ? 1 : 0;
    if (!valid(decoded, i)) continue;
    const double truth = v.trueProjectorPixel(static_cast<std::size_t>(i)).x();
    if (!std::isfinite(truth)) continue;
    errors.push_back(std::fabs(decoded.column.ptr<float>(0)[i] - truth));
    far_off += errors.back() > far ? 1 : 0;
  }
  if (errors.empty()) return {};
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  return {static_cast<double>(errors.size()) / std::max(measurable, 1), errors[errors.size() / 2],
          static_cast<double>(far_off) / errors.size()};
}

// A complementary Gray code (Zhang et al. 2012) counts half periods only, one bit more than the
// periods need, and the phase places the pixel inside its word: 4 Gray pairs fewer per axis at a
// period of 16, the same coverage and no pixel a period off.
TEST(RigSequences, AComplementaryGrayCodeUnwrapsThePhaseAsTheFullCodeDoes) {
  for (const int period : {16, 32}) {
    CaptureOptions full = smallOptions();
    full.phase_period = period;
    CaptureOptions complementary = full;
    complementary.gray_unit = period / 2;
    const testing::VirtualCapture& reference = virtualCapture(full);
    const testing::VirtualCapture& v = virtualCapture(complementary);
    const TruthAgreement ours = againstTruth(reference, decodeCapture(reference.capture), 2.0);
    const TruthAgreement theirs = againstTruth(v, decodeCapture(v.capture), 2.0);
    const int fewer = period == 16 ? 2 * (3 + 3) : 2 * (4 + 4);  // Gray pairs of columns and rows
    EXPECT_EQ(v.capture.images.size() + static_cast<std::size_t>(fewer), reference.capture.images.size());
    EXPECT_GT(theirs.coverage, ours.coverage - 0.01) << "period " << period;
    EXPECT_LT(theirs.median_px, 0.3) << "period " << period;
    EXPECT_LT(theirs.far_share, 0.002) << "period " << period;
    std::printf(
        "period %d: full Gray code %zu images, coverage %.3f, median %.3f px, beyond 2 px %.5f; "
        "complementary %zu images, %.3f, %.3f px, %.5f\n",
        period, reference.capture.images.size(), ours.coverage, ours.median_px, ours.far_share, v.capture.images.size(),
        theirs.coverage, theirs.median_px, theirs.far_share);
  }
}

}  // namespace
}  // namespace binpick::reconstruction

namespace binpick::reconstruction {
namespace {

io::PatternSetSpec projector(int width, int height, int code_step) {
  io::PatternSetSpec spec;
  spec.projector_width = width;
  spec.projector_height = height;
  spec.code_step = code_step;
  return spec;
}

// Another rig's phase steps may run the other way or start at another shift: the same images
// relabelled as such a rig's (step k of a rig running backwards shows our step N - k; of one
// starting a quarter period on, our step k + 1) decode to the same coordinates.
TEST(RigSequences, PhaseStepsRunningTheOtherWayOrOffsetDecodeAsOurs) {
  const io::Capture& capture = ours();
  const DecodedCapture reference = decodeCapture(capture);
  const int steps = capture.metadata.pattern_set.phase_steps;
  ASSERT_EQ(steps, 4);
  // The pattern each name shows in the other rig's convention: `theirs(k)` is our step index.
  const auto relabelled = [&](const std::function<int(int)>& ours_for_theirs, int direction, double offset_deg) {
    io::Capture other = capture;
    for (std::size_t i = 0; i < other.images.size(); ++i) {
      const std::string& name = capture.metadata.patterns[i];
      if (name.rfind("phase_", 0) != 0) continue;
      const int theirs = name.back() - '0';
      const std::string our_name = name.substr(0, name.size() - 1) + std::to_string(ours_for_theirs(theirs));
      const auto at = std::find(capture.metadata.patterns.begin(), capture.metadata.patterns.end(), our_name);
      other.images[i] = capture.images[static_cast<std::size_t>(at - capture.metadata.patterns.begin())];
    }
    other.metadata.pattern_set.phase_direction = direction;
    other.metadata.pattern_set.phase_offset_deg = offset_deg;
    return other;
  };
  const io::Capture backwards = relabelled([&](int k) { return (steps - k) % steps; }, -1, 0.0);
  const io::Capture quarter_on = relabelled([&](int k) { return (k + 1) % steps; }, 1, 90.0);
  for (const io::Capture* other : {&backwards, &quarter_on}) {
    const Agreement agreement = compare(reference, decodeCapture(*other), 1e-3);
    EXPECT_GT(agreement.coverage, 0.999);
    EXPECT_GT(agreement.agreeing, 0.999);
  }
  // Told as ours, the backwards steps are refused: they read as two swapped phase images.
  io::Capture untold = backwards;
  untold.metadata.pattern_set.phase_direction = 1;
  EXPECT_THROW(decodeCapture(untold), core::Error);
}

TEST(RigSequenceFiles, OpenCvsGrayCodePatternIsAPreset) {
  // OpenCV's GrayCodePattern for a 1920 x 1080 projector at 960 x 540 codes: 10 + 10 bits.
  const RigSequence sequence = presetSequence("opencv-graycode", projector(1920, 1080, 2));
  ASSERT_EQ(sequence.patterns.size(), 42u);
  EXPECT_EQ(sequence.patterns[0], "gray_col_00");
  EXPECT_EQ(sequence.patterns[1], "gray_col_00_inv");
  EXPECT_EQ(sequence.patterns[20], "gray_row_00");
  EXPECT_EQ(sequence.patterns[40], "white");
  EXPECT_EQ(sequence.patterns[41], "black");
  EXPECT_EQ(sequence.spec.phase_steps, 0);
  EXPECT_EQ(presetSequence("binpick", io::PatternSetSpec{}).patterns.size(), 52u);
  EXPECT_NE(binpick::test::thrownMessage([] { presetSequence("nope", io::PatternSetSpec{}); }).find("opencv-graycode"),
            std::string::npos);
}

TEST(RigSequenceFiles, AFileDescribesAnyOrderInversesBitOrderAndPhase) {
  const RigSequence sequence = parseRigSequence(R"(
projector: {width: 1024, height: 768}
phase: {steps: 4, period: 32, direction: -1, offset_deg: 90}
images:
  - phase: columns
  - gray: columns
    inverses: none
    order: lsb_first
  - white
  - black
)",
                                                "rig.yaml");
  EXPECT_TRUE(sequence.spec.column_codes);
  EXPECT_FALSE(sequence.spec.row_codes);
  EXPECT_EQ(sequence.spec.phase_direction, -1);
  EXPECT_EQ(sequence.spec.phase_offset_deg, 90.0);
  ASSERT_EQ(sequence.patterns.size(), 4u + 10u + 2u);
  EXPECT_EQ(sequence.patterns[0], "phase_col_0");
  EXPECT_EQ(sequence.patterns[4], "gray_col_09");
  EXPECT_EQ(sequence.patterns[13], "gray_col_00");
  EXPECT_EQ(sequence.patterns.back(), "black");

  const RigSequence complementary = parseRigSequence(R"(
projector: {width: 1024, height: 768}
gray_unit: 16
phase: {steps: 4, period: 32}
images: [white, black, {gray: columns}, {phase: columns}]
)",
                                                     "rig.yaml");
  EXPECT_EQ(complementary.spec.gray_unit, 16);
  EXPECT_EQ(complementary.patterns.size(), 2u + 2 * 6 + 4);  // 64 words of 16 columns: 6 bits

  const RigSequence after_all = parseRigSequence(
      "projector: {width: 8, height: 8}\nimages:\n  - {gray: columns, inverses: after_all}\n", "rig.yaml");
  EXPECT_EQ(after_all.patterns, (std::vector<std::string>{"gray_col_00", "gray_col_01", "gray_col_02",
                                                          "gray_col_00_inv", "gray_col_01_inv", "gray_col_02_inv"}));
}

TEST(RigSequenceFiles, MistakesAreNamed) {
  const auto error = [](const std::string& yaml) {
    return binpick::test::thrownMessage([&] { parseRigSequence(yaml, "rig.yaml"); });
  };
  EXPECT_NE(error("images: [white]\n").find("projector"), std::string::npos);
  EXPECT_NE(error("projector: {width: 64, height: 64}\nimages: [gray_col_7]\n").find("'gray_col_7' is no pattern"),
            std::string::npos);
  EXPECT_NE(error("projector: {width: 64, height: 64}\nimages: [gray_col_09]\n").find("beyond the 6 Gray bits"),
            std::string::npos);
  EXPECT_NE(error("projector: {width: 64, height: 64}\nimages: [{gray: diagonal}]\n").find("columns or rows"),
            std::string::npos);
  EXPECT_NE(error("projector: {width: 64, height: 64}\nimages: [{phase: columns}]\n").find("phase"), std::string::npos);
  EXPECT_NE(error("projector: {width: 64, height: 64}\nimages: [white, white, {gray: columns}]\n").find("twice"),
            std::string::npos);
  EXPECT_NE(error("projector: {width: 64, height: 64}\nimages: [{gray: rows}]\n").find("no column codes"),
            std::string::npos);
}

}  // namespace
}  // namespace binpick::reconstruction
