// The decoder against the virtual cell's truth: which projector pixel each camera pixel sees.
#include "binpick/reconstruction/decoder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "virtual_capture.hpp"

namespace binpick::reconstruction {
namespace {

using testing::CaptureOptions;
using testing::VirtualCapture;
using testing::virtualCapture;

bool isValid(const DecodedCapture& decoded, std::size_t pixel) {
  return decoded.status.ptr<uint8_t>(0)[pixel] == static_cast<uint8_t>(PixelStatus::Valid);
}

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(q * static_cast<double>(values.size() - 1))];
}

struct DecodeScore {
  double valid_fraction = 0.0;  // of the pixels an ideal sensor measures
  double median_error = 0.0;    // projector pixels, column
  double p99_error = 0.0;
  double median_row_error = 0.0;
  std::size_t wrong = 0;  // valid pixels more than 2 projector pixels off
  std::size_t valid = 0;
};

DecodeScore score(const VirtualCapture& v, const DecodedCapture& decoded) {
  DecodeScore s;
  std::size_t measurable = 0, measured = 0;
  std::vector<double> column_errors, row_errors;
  for (std::size_t i = 0; i < v.pixelCount(); ++i) {
    if (v.measurable(i)) {
      ++measurable;
      if (isValid(decoded, i)) ++measured;
    }
    if (!isValid(decoded, i)) continue;
    ++s.valid;
    const Eigen::Vector2d truth = v.trueProjectorPixel(i);
    const double column_error = std::fabs(decoded.column.ptr<float>(0)[i] - truth.x());
    if (!(column_error <= 2.0)) ++s.wrong;  // NaN truth (nothing there) counts as wrong
    column_errors.push_back(column_error);
    if (!decoded.row.empty()) row_errors.push_back(std::fabs(decoded.row.ptr<float>(0)[i] - truth.y()));
  }
  s.valid_fraction = static_cast<double>(measured) / static_cast<double>(measurable);
  s.median_error = percentile(column_errors, 0.5);
  s.p99_error = percentile(column_errors, 0.99);
  s.median_row_error = percentile(row_errors, 0.5);
  return s;
}

// Full resolution, Gray code and 4-step phase shift on both axes: the default pattern set.
TEST(Decoder, FindsTheProjectorPixelOfAlmostEveryLitPixelToAFractionOfAPixel) {
  const VirtualCapture& v = virtualCapture({});
  const DecodedCapture decoded = decodeCapture(v.capture);
  ASSERT_EQ(decoded.width, v.capture.metadata.image_width);
  EXPECT_TRUE(decoded.has_phase);
  const DecodeScore s = score(v, decoded);
  EXPECT_GT(s.valid_fraction, 0.97);
  EXPECT_LT(s.median_error, 0.1);
  EXPECT_LT(s.p99_error, 0.6);
  EXPECT_LT(s.median_row_error, 0.1);
  EXPECT_LE(s.wrong, s.valid / 10000);
}

TEST(Decoder, LeavesPixelsInProjectorShadowInvalid) {
  const VirtualCapture& v = virtualCapture({});
  const DecodedCapture decoded = decodeCapture(v.capture);
  const int width = decoded.width;
  std::size_t shadowed = 0, decoded_in_shadow = 0;
  for (int y = 1; y + 1 < decoded.height; ++y) {
    for (int x = 1; x + 1 < width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * width + x;
      // Deep in the shadow: the neighbours too, so that no part of the pixel's footprint is lit.
      if (!(v.inShadow(i) && v.inShadow(i - 1) && v.inShadow(i + 1) && v.inShadow(i - width) &&
            v.inShadow(i + width))) {
        continue;
      }
      ++shadowed;
      if (isValid(decoded, i)) ++decoded_in_shadow;
      EXPECT_TRUE(std::isnan(decoded.column.ptr<float>(0)[i]));
    }
  }
  ASSERT_GT(shadowed, 1000u);  // the pile casts shadows: the test checks something
  EXPECT_EQ(decoded_in_shadow, 0u);
}

TEST(Decoder, GrayCodeAloneIsAccurateToItsQuantisation) {
  CaptureOptions options;
  options.phase_steps = 0;
  const VirtualCapture& v = virtualCapture(options);
  const DecodedCapture decoded = decodeCapture(v.capture);
  EXPECT_FALSE(decoded.has_phase);
  const DecodeScore s = score(v, decoded);
  EXPECT_GT(s.valid_fraction, 0.9);
  EXPECT_LT(s.median_error, 0.35);  // uniform within a column: 0.25 on average
  EXPECT_LT(s.p99_error, 1.0);
  EXPECT_LE(s.wrong, s.valid / 10000);
}

// Strong interreflections (half of the direct light again, from elsewhere) and room light. Where
// global light outweighs direct light twice over, Moreno & Taubin's rules give up on a bit
// rather than guess: fewer points, none wrong.
TEST(Decoder, StaysCorrectUnderStrongIndirectAndAmbientLight) {
  CaptureOptions options;
  options.camera_scale = 0.5;
  options.global_light = 0.5;
  options.ambient = 40.0;
  const VirtualCapture& v = virtualCapture(options);
  const DecodeScore s = score(v, decodeCapture(v.capture));
  EXPECT_GT(s.valid_fraction, 0.85);
  EXPECT_LT(s.median_error, 0.15);
  EXPECT_LE(s.wrong, s.valid / 10000);
}

// Diffuse interreflection from nearby surfaces carries the pattern's coarse stripes (and averages
// the fine ones to half): each image plus a strongly blurred copy of itself. The global share
// then differs between a coarse pattern and its inverse, which can flip naive bits; they must
// become invalid, not wrong.
TEST(Decoder, MarksBitsThatPatternedInterreflectionWouldFlipInvalidInsteadOfWrong) {
  CaptureOptions options;
  options.camera_scale = 0.5;
  const VirtualCapture& v = virtualCapture(options);
  io::Capture reflected = testing::deepCopy(v.capture);
  for (cv::Mat& image : reflected.images) {
    cv::Mat blurred;
    cv::GaussianBlur(image, blurred, cv::Size(), 15.0);
    cv::addWeighted(image, 1.0, blurred, 1.0, 0.0, image);
  }
  const DecodeScore s = score(v, decodeCapture(reflected));
  EXPECT_LE(s.wrong, s.valid / 1000);
  EXPECT_GT(s.valid_fraction, 0.8);
}

// A projector out of focus (1.5 px blur), Gray code alone: the 1-pixel stripes are gone and the
// 2-pixel ones keep less than a tenth of the direct light. That was below the old margin (15% of
// L_d): the bit was uncertain, the code left 4 columns open and the pixel was lost. The sensor's
// noise (measured on the capture) is far smaller than that tenth: the margin capped by it
// decides the bit, and correctly.
TEST(Decoder, DecidesDefocusedFineBitsThatStandWellAboveTheNoise) {
  CaptureOptions options;
  options.camera_scale = 0.5;
  options.phase_steps = 0;
  options.projector_blur = 1.5;
  const VirtualCapture& v = virtualCapture(options);
  DecodeParams old_margin;
  old_margin.bit_noise_sigmas = 0.0;
  const DecodeScore before = score(v, decodeCapture(v.capture, old_margin));
  const DecodeScore after = score(v, decodeCapture(v.capture));
  EXPECT_GT(after.valid_fraction, before.valid_fraction + 0.1) << before.valid_fraction;
  EXPECT_GT(after.valid_fraction, 0.8);
  EXPECT_LT(after.median_error, 0.35);  // Gray code alone: within a column
  EXPECT_LE(after.wrong, after.valid / 10000);
}

// The capture as a black surface would give it: the projector's light scaled down to `share`
// (a few counts of contrast, as on the real data set's black squares) with the sensor's noise
// (sigma counts, seeded) added to every image.
io::Capture darkened(const io::Capture& capture, int black_index, double share, double sigma) {
  io::Capture dark = testing::deepCopy(capture);
  cv::RNG rng(11);
  cv::Mat black;
  capture.images.at(static_cast<std::size_t>(black_index)).convertTo(black, CV_32F);
  for (cv::Mat& image : dark.images) {
    cv::Mat light, noise(image.size(), CV_32F);
    image.convertTo(light, CV_32F);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, sigma);
    cv::Mat scaled = black + share * (light - black) + noise;
    scaled.convertTo(image, image.type());  // rounds and saturates
  }
  return dark;
}

// A dark surface under a defocused projector, Gray code alone: 8% of the light, the finest bits a
// count or two, under the noise margin. Read along their stripes (stripe_reading.hpp), more
// pixels get a column, within the run of codes their readable bits leave, and none in shadow.
// Measured when written: 66.9% of the measurable pixels alone, 1953 more along their stripes,
// 2.7% of those outside their run (at depth edges), median error 0.44 projector px.
TEST(Decoder, ReadsADarkSurfaceAlongItsStripes) {
  CaptureOptions options;
  options.phase_steps = 0;
  options.code_step = 2;
  options.projector_blur = 1.5;
  const VirtualCapture& v = virtualCapture(options);
  const io::Capture dark = darkened(v.capture, 1, 0.08, 1.0);  // image 1: black
  DecodeParams alone;
  alone.stripe_reach = 0;
  const DecodeScore before = score(v, decodeCapture(dark, alone));
  const DecodedCapture decoded = decodeCapture(dark);
  const DecodeScore after = score(v, decoded);
  std::size_t along = 0, outside_run = 0, in_shadow = 0;
  std::vector<double> errors;
  for (std::size_t i = 0; i < v.pixelCount(); ++i) {
    if (!isValid(decoded, i) || decoded.stripe_run.ptr<uint8_t>(0)[i] == 0) continue;
    ++along;
    if (v.inShadow(i)) ++in_shadow;
    const double error = std::fabs(decoded.column.ptr<float>(0)[i] - v.trueProjectorPixel(i).x());
    errors.push_back(error);
    if (!(error <= 0.5 * decoded.stripe_run.ptr<uint8_t>(0)[i] + 1.0)) ++outside_run;
  }
  SCOPED_TRACE("valid alone " + std::to_string(before.valid_fraction) + ", along stripes " +
               std::to_string(after.valid_fraction) + "; " + std::to_string(along) + " read along, " +
               std::to_string(outside_run) + " outside their run, median error " +
               std::to_string(percentile(errors, 0.5)));
  EXPECT_GT(along, 1000u);
  EXPECT_GT(after.valid_fraction, before.valid_fraction);
  EXPECT_LT(percentile(errors, 0.5), 1.0);  // projector pixels
  EXPECT_LE(outside_run, along / 20);
  EXPECT_EQ(in_shadow, 0u);
}

TEST(Decoder, SixteenBitImagesDecodeLikeEightBitOnes) {
  CaptureOptions eight;
  eight.camera_scale = 0.5;
  CaptureOptions sixteen = eight;
  sixteen.bit_depth = 16;
  const DecodeScore a = score(virtualCapture(eight), decodeCapture(virtualCapture(eight).capture));
  const DecodeScore b = score(virtualCapture(sixteen), decodeCapture(virtualCapture(sixteen).capture));
  EXPECT_NEAR(a.valid_fraction, b.valid_fraction, 0.02);
  EXPECT_LT(b.median_error, 0.15);
  EXPECT_LE(b.wrong, b.valid / 10000);
}

TEST(Decoder, ColumnsOnlyCapturesGiveNoRows) {
  CaptureOptions options;
  options.camera_scale = 0.5;
  options.row_codes = false;
  const VirtualCapture& v = virtualCapture(options);
  const DecodedCapture decoded = decodeCapture(v.capture);
  EXPECT_TRUE(decoded.row.empty());
  const DecodeScore s = score(v, decoded);
  EXPECT_GT(s.valid_fraction, 0.9);
  EXPECT_LE(s.wrong, s.valid / 10000);
}

TEST(Decoder, GivesTheSameResultOnAnyNumberOfThreads) {
  CaptureOptions options;
  options.camera_scale = 0.5;
  const io::Capture& capture = virtualCapture(options).capture;
  DecodeParams one;
  one.threads = 1;
  DecodeParams two;
  two.threads = 2;
  const DecodedCapture a = decodeCapture(capture, one);
  const DecodedCapture b = decodeCapture(capture, two);
  EXPECT_EQ(cv::norm(a.status, b.status, cv::NORM_INF), 0.0);
  EXPECT_EQ(0, std::memcmp(a.column.data, b.column.data, a.column.total() * sizeof(float)));
  EXPECT_EQ(cv::norm(a.intensity, b.intensity, cv::NORM_INF), 0.0);
  ASSERT_FALSE(a.column_noise.empty());
  EXPECT_EQ(0, std::memcmp(a.column_noise.data, b.column_noise.data, a.column_noise.total() * sizeof(float)));
}

CaptureOptions harshOptions() {
  CaptureOptions options;
  options.camera_scale = 0.5;
  options.lighting = "harsh";
  return options;
}

// Under harsh light the sensor noise leaves coarse Gray bits of the dark parts undecided; their
// neighbours name the phase's period. More pixels decode, and those the neighbours resolved are
// as close to the true column as the phase is.
TEST(Decoder, UnwrapsUncertainCodesOnDarkSurfacesFromTheirNeighbours) {
  const VirtualCapture& v = virtualCapture(harshOptions());
  DecodeParams alone;
  alone.min_unwrap_neighbours = 0;
  const DecodedCapture before = decodeCapture(v.capture, alone);
  const DecodedCapture after = decodeCapture(v.capture);
  std::size_t resolved = 0, off = 0;
  for (std::size_t i = 0; i < v.pixelCount(); ++i) {
    if (isValid(before, i)) {
      EXPECT_EQ(before.column.ptr<float>(0)[i], after.column.ptr<float>(0)[i]) << i;  // the first pass stands
      continue;
    }
    if (!isValid(after, i)) continue;
    ++resolved;
    EXPECT_EQ(before.status.ptr<uint8_t>(0)[i], static_cast<uint8_t>(PixelStatus::UncertainCode)) << i;
    const double error = std::fabs(after.column.ptr<float>(0)[i] - v.trueProjectorPixel(i).x());
    off += error <= 2.0 ? 0 : 1;  // NaN truth: off
  }
  EXPECT_GT(resolved, 500u);  // 677 measured
  EXPECT_LE(off, resolved / 100) << resolved;
}

// The column's noise predicted from the sensor noise measured on the capture and each pixel's
// phase amplitude is the spread of the decoded columns about the truth (their rms within 15% of
// each other): a few hundredths of a projector pixel on the bright clean parts, tenths on the
// dark parts under harsh light.
TEST(Decoder, PredictsTheNoiseOfEachColumn) {
  CaptureOptions clean_options;
  clean_options.camera_scale = 0.5;
  for (const CaptureOptions& options : {clean_options, harshOptions()}) {
    const VirtualCapture& v = virtualCapture(options);
    const DecodedCapture decoded = decodeCapture(v.capture);
    ASSERT_FALSE(decoded.column_noise.empty());
    std::vector<double> predicted;
    double squared_error = 0.0, squared_prediction = 0.0;
    for (std::size_t i = 0; i < v.pixelCount(); ++i) {
      const float sigma = decoded.column_noise.ptr<float>(0)[i];
      if (!isValid(decoded, i)) {
        EXPECT_TRUE(std::isnan(sigma)) << i;
        continue;
      }
      const double error = decoded.column.ptr<float>(0)[i] - v.trueProjectorPixel(i).x();
      if (!v.measurable(i) || v.scene.instance[i] < 0 || !(std::fabs(error) < 2.0)) continue;  // the parts' faces
      predicted.push_back(sigma);
      squared_error += error * error;
      squared_prediction += static_cast<double>(sigma) * sigma;
    }
    const double ratio = std::sqrt(squared_error / squared_prediction);
    SCOPED_TRACE(options.lighting + ": median predicted " + std::to_string(percentile(predicted, 0.5)) +
                 " px, rms error / rms predicted " + std::to_string(ratio));
    if (options.lighting == "clean") {
      EXPECT_LT(percentile(predicted, 0.5), 0.1);  // 0.045 measured
    } else {
      EXPECT_GT(percentile(predicted, 0.5), 0.3);  // 0.38 measured
    }
    EXPECT_GT(ratio, 0.85);  // 1.01 (clean) and 1.00 (harsh) measured
    EXPECT_LT(ratio, 1.15);
  }
}

TEST(Decoder, IntensityIsTheWhiteImageOnTheSensorsScale) {
  CaptureOptions options;
  options.camera_scale = 0.5;
  const io::Capture& capture = virtualCapture(options).capture;
  const DecodedCapture decoded = decodeCapture(capture);
  cv::Mat white;
  capture.images[0].convertTo(white, CV_32F, 1.0 / 255.0);
  EXPECT_LT(cv::norm(decoded.intensity, white, cv::NORM_INF), 1e-6);
}

}  // namespace
}  // namespace binpick::reconstruction
