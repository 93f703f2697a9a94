// renderPatternImages: per-pixel lighting -> one camera image per projected pattern.
#include "binpick/simulation/pattern_renderer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/reconstruction/pattern_set.hpp"
#include "thrown_message.hpp"

namespace binpick::simulation {
namespace {

namespace rc = binpick::reconstruction;

constexpr float kSharp = 1e-4f;  // blur sigma far below a projector pixel

PhotometryParams noiseless() {
  PhotometryParams params;
  params.read_noise = 0.0;
  params.shot_noise_gain = 0.0;
  params.projector_black_level = 0.01;
  params.threads = 1;
  return params;
}

PixelLighting lit(float x, float y, float sigma, float direct, float ambient, float global = 0.0f) {
  PixelLighting p;
  p.projector_x = x;
  p.projector_y = y;
  p.blur_sigma = sigma;
  p.direct = direct;
  p.ambient = ambient;
  p.global = global;
  return p;
}

// Varied lighting over a width x height image, from a seeded generator.
std::vector<PixelLighting> variedLighting(int width, int height, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<PixelLighting> pixels;
  for (int i = 0; i < width * height; ++i) {
    pixels.push_back(lit(1279.0f * unit(rng), 799.0f * unit(rng), 3.0f * unit(rng), 250.0f * unit(rng),
                         20.0f * unit(rng), 10.0f * unit(rng)));
  }
  return pixels;
}

// Gray-code bit `index` (0 = most significant) of `coordinate` among `bits`, computed here
// from the definition rather than by the library.
bool grayBit(int coordinate, int bits, int index) {
  const unsigned gray = static_cast<unsigned>(coordinate) ^ (static_cast<unsigned>(coordinate) >> 1);
  return ((gray >> (bits - 1 - index)) & 1u) != 0;
}

// Index of a named pattern in the sequence of `spec`.
std::size_t indexOf(const io::PatternSetSpec& spec, const std::string& name) {
  const std::vector<std::string> names = rc::patternNames(spec);
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) ADD_FAILURE() << "no pattern " << name;
  return static_cast<std::size_t>(it - names.begin());
}

std::string grayName(const char* axis, int bit, bool inverse) {
  char text[32];
  std::snprintf(text, sizeof text, "gray_%s_%02d%s", axis, bit, inverse ? "_inv" : "");
  return text;
}

bool identical(const std::vector<cv::Mat>& a, const std::vector<cv::Mat>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].type() != b[i].type() || a[i].size() != b[i].size() || cv::norm(a[i], b[i], cv::NORM_INF) != 0.0) {
      return false;
    }
  }
  return true;
}

::testing::AssertionResult throwsNaming(const std::vector<PixelLighting>& pixels, int width, int height,
                                        const io::PatternSetSpec& spec, const PhotometryParams& params,
                                        const std::string& text) {
  return binpick::test::throwsNaming([&] { renderPatternImages(pixels, width, height, spec, params); }, text);
}

TEST(PatternRenderer, OneImagePerPatternOfTheRequestedSizeAndDepth) {
  const io::PatternSetSpec spec;
  PhotometryParams params = noiseless();
  const std::vector<PixelLighting> pixels(5 * 3, lit(10.0f, 10.0f, kSharp, 100.0f, 5.0f));
  std::vector<cv::Mat> images = renderPatternImages(pixels, 5, 3, spec, params);
  ASSERT_EQ(images.size(), rc::patternSequence(spec).size());
  for (const cv::Mat& image : images) {
    EXPECT_EQ(image.type(), CV_8UC1);
    EXPECT_EQ(image.size(), cv::Size(5, 3));
  }
  params.bit_depth = 16;
  images = renderPatternImages(pixels, 5, 3, spec, params);
  for (const cv::Mat& image : images) EXPECT_EQ(image.type(), CV_16UC1);
}

TEST(PatternRenderer, SharpPixelReadsEachGrayBitOfItsColumnAndRow) {
  const io::PatternSetSpec spec;  // 1280 x 800: 11 column bits, 10 row bits
  const std::vector<PixelLighting> pixels{
      lit(100.0f, 37.0f, kSharp, 160.0f, 6.0f), lit(1279.0f, 799.0f, kSharp, 160.0f, 6.0f),
      lit(0.0f, 0.0f, kSharp, 160.0f, 6.0f), lit(682.0f, 341.0f, kSharp, 160.0f, 6.0f)};
  const std::vector<cv::Mat> images = renderPatternImages(pixels, 4, 1, spec, noiseless());
  const int on = 166;  // ambient + direct
  const int off = 8;   // ambient + direct * black level (7.6)
  for (int px = 0; px < 4; ++px) {
    const int column = static_cast<int>(pixels[px].projector_x);
    const int row = static_cast<int>(pixels[px].projector_y);
    for (int bit = 0; bit < 11; ++bit) {
      const bool set = grayBit(column, 11, bit);
      EXPECT_EQ(images[indexOf(spec, grayName("col", bit, false))].at<uchar>(0, px), set ? on : off)
          << "column " << column << " bit " << bit;
      EXPECT_EQ(images[indexOf(spec, grayName("col", bit, true))].at<uchar>(0, px), set ? off : on)
          << "column " << column << " inverse bit " << bit;
    }
    for (int bit = 0; bit < 10; ++bit) {
      const bool set = grayBit(row, 10, bit);
      EXPECT_EQ(images[indexOf(spec, grayName("row", bit, false))].at<uchar>(0, px), set ? on : off)
          << "row " << row << " bit " << bit;
      EXPECT_EQ(images[indexOf(spec, grayName("row", bit, true))].at<uchar>(0, px), set ? off : on)
          << "row " << row << " inverse bit " << bit;
    }
  }
}

TEST(PatternRenderer, WhiteAndBlackReadAmbientPlusDirectPlusGlobal) {
  const io::PatternSetSpec spec;
  const float ambient = 6.2f, direct = 150.3f, global = 4.4f;
  const std::vector<PixelLighting> pixels{lit(400.0f, 300.0f, 0.4f, direct, ambient, global)};
  PhotometryParams params = noiseless();
  const double white = ambient + direct + global;
  const double black = ambient + params.projector_black_level * (direct + global);

  std::vector<cv::Mat> images = renderPatternImages(pixels, 1, 1, spec, params);
  EXPECT_NEAR(images[indexOf(spec, "white")].at<uchar>(0, 0), white, 0.5);
  EXPECT_NEAR(images[indexOf(spec, "black")].at<uchar>(0, 0), black, 0.5);

  params.bit_depth = 16;  // the 8-bit counts scaled by 257
  images = renderPatternImages(pixels, 1, 1, spec, params);
  EXPECT_NEAR(images[indexOf(spec, "white")].at<uint16_t>(0, 0), 257.0 * white, 0.5);
  EXPECT_NEAR(images[indexOf(spec, "black")].at<uint16_t>(0, 0), 257.0 * black, 0.5);
}

TEST(PatternRenderer, PhaseImagesFollowTheProjectedSine) {
  io::PatternSetSpec spec;
  spec.phase_period = 16;
  const float direct = 200.0f, ambient = 10.0f;
  const std::vector<PixelLighting> pixels{lit(4.0f, 8.0f, kSharp, direct, ambient)};
  const std::vector<cv::Mat> images = renderPatternImages(pixels, 1, 1, spec, noiseless());
  // Column 4 is a quarter period (phase pi/2): step 1 at its brightest, step 3 at its darkest.
  EXPECT_EQ(images[indexOf(spec, "phase_col_1")].at<uchar>(0, 0), 210);
  EXPECT_EQ(images[indexOf(spec, "phase_col_3")].at<uchar>(0, 0), 12);  // 10 + 200 * 0.01
  // Row 8 is half a period (phase pi): step 2 at its brightest, step 0 at its darkest.
  EXPECT_EQ(images[indexOf(spec, "phase_row_2")].at<uchar>(0, 0), 210);
  EXPECT_EQ(images[indexOf(spec, "phase_row_0")].at<uchar>(0, 0), 12);
}

TEST(PatternRenderer, SameSeedGivesTheSameImagesOnAnyNumberOfThreads) {
  const io::PatternSetSpec spec;
  const std::vector<PixelLighting> pixels = variedLighting(37, 23, 11);
  PhotometryParams params;
  params.seed = 42;
  params.threads = 1;
  const std::vector<cv::Mat> one = renderPatternImages(pixels, 37, 23, spec, params);
  EXPECT_TRUE(identical(one, renderPatternImages(pixels, 37, 23, spec, params)));
  params.threads = 2;
  EXPECT_TRUE(identical(one, renderPatternImages(pixels, 37, 23, spec, params)));
  params.threads = 3;
  EXPECT_TRUE(identical(one, renderPatternImages(pixels, 37, 23, spec, params)));
  params.seed = 43;
  EXPECT_FALSE(identical(one, renderPatternImages(pixels, 37, 23, spec, params)));
}

TEST(PatternRenderer, NoiseHasTheModelledMeanAndSpread) {
  const io::PatternSetSpec spec;
  constexpr int kSide = 64;
  const double signal = 105.0;  // white: ambient 5 + direct 100
  const std::vector<PixelLighting> pixels(kSide * kSide, lit(50.0f, 50.0f, 0.4f, 100.0f, 5.0f));
  PhotometryParams params;
  params.read_noise = 0.7;
  params.shot_noise_gain = 0.03;
  params.seed = 9;
  const cv::Mat white = renderPatternImages(pixels, kSide, kSide, spec, params)[indexOf(spec, "white")];
  cv::Scalar mean, deviation;
  cv::meanStdDev(white, mean, deviation);
  // Read and shot noise, plus the 1/12 count^2 of rounding to integers.
  const double expected = std::sqrt(0.7 * 0.7 + 0.03 * signal + 1.0 / 12.0);
  EXPECT_NEAR(mean[0], signal, 0.15);
  EXPECT_NEAR(deviation[0], expected, 0.05 * expected);
}

TEST(PatternRenderer, SaturatesAtFullScale) {
  const io::PatternSetSpec spec;
  const std::vector<PixelLighting> pixels(6, lit(100.0f, 100.0f, 0.4f, 1000.0f, 30.0f));
  PhotometryParams params;  // with noise
  std::vector<cv::Mat> images = renderPatternImages(pixels, 3, 2, spec, params);
  double low = 0.0, high = 0.0;
  cv::minMaxLoc(images[indexOf(spec, "white")], &low, &high);
  EXPECT_EQ(low, 255.0);
  EXPECT_EQ(high, 255.0);

  params.bit_depth = 16;
  images = renderPatternImages(pixels, 3, 2, spec, params);
  cv::minMaxLoc(images[indexOf(spec, "white")], &low, &high);
  EXPECT_EQ(low, 65535.0);
  EXPECT_EQ(high, 65535.0);
}

TEST(PatternRenderer, DarkPixelsClampAtZeroInsteadOfWrapping) {
  const io::PatternSetSpec spec;
  const std::vector<PixelLighting> pixels(32 * 32, lit(100.0f, 100.0f, 0.4f, 0.0f, 0.0f));
  PhotometryParams params;
  params.read_noise = 3.0;
  for (int depth : {8, 16}) {
    params.bit_depth = depth;
    const cv::Mat black = renderPatternImages(pixels, 32, 32, spec, params)[indexOf(spec, "black")];
    double low = 0.0, high = 0.0;
    cv::minMaxLoc(black, &low, &high);
    EXPECT_EQ(low, 0.0) << depth << " bit";
    EXPECT_LT(high, 15.0 * (depth == 16 ? 257.0 : 1.0)) << depth << " bit";  // 5 sigma
  }
}

TEST(PatternRenderer, DefocusWashesOutFineBitsBeforeCoarseOnes) {
  const io::PatternSetSpec spec;  // 11 column bits; bit 10 has stripes two columns wide
  const std::vector<PixelLighting> pixels{lit(101.0f, 50.0f, kSharp, 200.0f, 5.0f),
                                          lit(101.0f, 50.0f, 2.5f, 200.0f, 5.0f)};
  const std::vector<cv::Mat> images = renderPatternImages(pixels, 2, 1, spec, noiseless());
  auto contrast = [&](int bit, int px) {
    return std::abs(int(images[indexOf(spec, grayName("col", bit, false))].at<uchar>(0, px)) -
                    int(images[indexOf(spec, grayName("col", bit, true))].at<uchar>(0, px)));
  };
  const int full = 198;  // direct * (1 - black level)
  EXPECT_EQ(contrast(0, 0), full);
  EXPECT_EQ(contrast(10, 0), full);
  // Column 101 is 900 columns from the most significant bit's edge: defocus leaves it alone.
  EXPECT_NEAR(contrast(0, 1), full, 1);
  EXPECT_LT(contrast(10, 1), full / 10);
  EXPECT_LT(contrast(10, 1), contrast(0, 1));
  EXPECT_LT(contrast(9, 1), contrast(5, 1));
}

TEST(PatternRenderer, UnlitPixelReadsTheSameUnderABitAndItsInverse) {
  const io::PatternSetSpec spec;
  constexpr int kSide = 32;
  const std::vector<PixelLighting> pixels(kSide * kSide, lit(640.0f, 400.0f, 0.4f, 0.0f, 30.0f));
  // Without noise: identical.
  std::vector<cv::Mat> images = renderPatternImages(pixels, kSide, kSide, spec, noiseless());
  for (int bit = 0; bit < 11; ++bit) {
    EXPECT_EQ(cv::norm(images[indexOf(spec, grayName("col", bit, false))],
                       images[indexOf(spec, grayName("col", bit, true))], cv::NORM_INF),
              0.0)
        << "bit " << bit;
  }
  // With noise: the same up to noise (sigma ~1.2 counts per image), no bias.
  PhotometryParams params;
  params.read_noise = 0.7;
  params.shot_noise_gain = 0.03;
  images = renderPatternImages(pixels, kSide, kSide, spec, params);
  for (int bit = 0; bit < 11; ++bit) {
    cv::Mat difference;
    cv::subtract(images[indexOf(spec, grayName("col", bit, false))], images[indexOf(spec, grayName("col", bit, true))],
                 difference, cv::noArray(), CV_32F);
    EXPECT_NEAR(cv::mean(difference)[0], 0.0, 0.25) << "bit " << bit;
    EXPECT_LT(cv::norm(difference, cv::NORM_INF), 10.0) << "bit " << bit;
  }
}

TEST(PatternRenderer, IndirectLightFollowsThePatternsMeanBrightness) {
  const io::PatternSetSpec spec;
  // Not lit directly, yet the bin reflects light of a white projection onto it.
  const std::vector<PixelLighting> pixels{lit(640.0f, 400.0f, 0.4f, 0.0f, 10.0f, 20.0f)};
  const std::vector<cv::Mat> images = renderPatternImages(pixels, 1, 1, spec, noiseless());
  EXPECT_EQ(images[indexOf(spec, "white")].at<uchar>(0, 0), 30);
  EXPECT_EQ(images[indexOf(spec, "black")].at<uchar>(0, 0), 10);  // 10 + 20 * 0.01
}

TEST(PatternRenderer, CodedPatternsDoNotReachPointsOutsideTheProjectorImage) {
  // Whether a point is lit at all is the lighting's business (direct = 0 when not): here only the
  // striped patterns are checked, which must not light a point beside or far off the image.
  const io::PatternSetSpec spec;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<PixelLighting> pixels{
      lit(-3.0f, 10.0f, kSharp, 200.0f, 7.0f), lit(1283.0f, 10.0f, kSharp, 200.0f, 7.0f),
      lit(1e20f, 10.0f, 1.0f, 200.0f, 7.0f),   lit(-1e20f, 10.0f, 1.0f, 200.0f, 7.0f),
      lit(nan, 10.0f, 1.0f, 200.0f, 7.0f),     lit(20.0f, 1e12f, 1.0f, 200.0f, 7.0f)};
  const std::vector<cv::Mat> images = renderPatternImages(pixels, 6, 1, spec, noiseless());
  for (int px = 0; px < 5; ++px) {
    for (int bit = 0; bit < 11; ++bit) {
      EXPECT_EQ(images[indexOf(spec, grayName("col", bit, false))].at<uchar>(0, px), 7)
          << "pixel " << px << " bit " << bit;
    }
    EXPECT_EQ(images[indexOf(spec, "phase_col_0")].at<uchar>(0, px), 7) << "pixel " << px;
  }
  for (int bit = 0; bit < 10; ++bit) {
    EXPECT_EQ(images[indexOf(spec, grayName("row", bit, true))].at<uchar>(0, 5), 7) << bit;
  }
}

// A pixel that sees two surfaces gathers each by its share: under every pattern it reads the mean
// of the two as seen alone, whatever its own entry says.
TEST(PatternRenderer, MixedPixelGathersEachSurfaceByItsShare) {
  const io::PatternSetSpec spec;
  const PixelLighting near = lit(100.0f, 37.0f, 0.5f, 160.0f, 6.0f, 4.0f);
  const PixelLighting far = lit(900.0f, 600.0f, 1.5f, 60.0f, 3.0f, 2.0f);
  const std::vector<PixelLighting> pixels{near, far, lit(500.0f, 400.0f, kSharp, 250.0f, 20.0f)};
  MixedPixels mixed;
  mixed.pixel = {2};
  mixed.first = {0, 2};
  mixed.surfaces = {{near, 0.5f}, {far, 0.5f}};
  const std::vector<cv::Mat> images = renderPatternImages(pixels, 3, 1, spec, noiseless(), mixed);
  for (std::size_t k = 0; k < images.size(); ++k) {
    const double mean = 0.5 * (images[k].at<uchar>(0, 0) + images[k].at<uchar>(0, 1));
    EXPECT_NEAR(images[k].at<uchar>(0, 2), mean, 1.0) << "image " << k;
  }
  // A share of what the pixel gathers sees nothing: the white image reads less.
  mixed.surfaces = {{near, 0.25f}};
  mixed.first = {0, 1};
  const cv::Mat white = renderPatternImages(pixels, 3, 1, spec, noiseless(), mixed)[indexOf(spec, "white")];
  EXPECT_NEAR(white.at<uchar>(0, 2), 0.25 * white.at<uchar>(0, 0), 1.0);
}

TEST(PatternRenderer, BadMixedPixelsAreNamed) {
  const io::PatternSetSpec spec;
  const std::vector<PixelLighting> pixels(4, lit(10.0f, 10.0f, kSharp, 100.0f, 5.0f));
  const auto message = [&](const MixedPixels& mixed) {
    return test::thrownMessage([&] { renderPatternImages(pixels, 2, 2, spec, noiseless(), mixed); });
  };
  MixedPixels mixed;
  mixed.pixel = {4};
  mixed.first = {0, 1};
  mixed.surfaces = {{pixels[0], 1.0f}};
  EXPECT_NE(message(mixed).find("mixed pixel 4 is outside the image"), std::string::npos) << message(mixed);
  mixed.pixel = {1, 1};
  mixed.first = {0, 1, 1};
  EXPECT_NE(message(mixed).find("mixed pixel 1 is listed twice"), std::string::npos) << message(mixed);
  mixed.pixel = {1};
  mixed.first = {0, 2};
  EXPECT_NE(message(mixed).find("does not split their 1 surfaces among 1 pixels"), std::string::npos)
      << message(mixed);
  mixed.first = {0, 1};
  mixed.surfaces[0].share = 1.5f;
  EXPECT_NE(message(mixed).find("share 1.5"), std::string::npos) << message(mixed);
}

TEST(PatternRenderer, WrongPixelCountIsNamed) {
  const io::PatternSetSpec spec;
  const std::vector<PixelLighting> pixels(5);
  EXPECT_TRUE(throwsNaming(pixels, 2, 3, spec, noiseless(), "5 pixels for a 2x3 image"));
  EXPECT_TRUE(throwsNaming({}, 0, 0, spec, noiseless(), "0 pixels for a 0x0 image"));
  EXPECT_TRUE(throwsNaming(pixels, -5, -1, spec, noiseless(), "for a -5x-1 image"));
}

TEST(PatternRenderer, BadParamsAreNamed) {
  const io::PatternSetSpec spec;
  const std::vector<PixelLighting> pixels(1);
  PhotometryParams params = noiseless();
  params.bit_depth = 12;
  EXPECT_TRUE(throwsNaming(pixels, 1, 1, spec, params, "PhotometryParams.bit_depth"));
  params = noiseless();
  params.read_noise = -0.1;
  EXPECT_TRUE(throwsNaming(pixels, 1, 1, spec, params, "PhotometryParams.read_noise"));
  params = noiseless();
  params.shot_noise_gain = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(throwsNaming(pixels, 1, 1, spec, params, "PhotometryParams.shot_noise_gain"));
  params = noiseless();
  params.projector_black_level = 1.0;
  EXPECT_TRUE(throwsNaming(pixels, 1, 1, spec, params, "PhotometryParams.projector_black_level"));
  params = noiseless();
  params.threads = -1;
  EXPECT_TRUE(throwsNaming(pixels, 1, 1, spec, params, "PhotometryParams.threads"));
  params = noiseless();
  params.mixed_pixel_samples = 0;
  EXPECT_TRUE(throwsNaming(pixels, 1, 1, spec, params, "PhotometryParams.mixed_pixel_samples"));
  params = noiseless();
  params.camera_blur_sigma = -0.5;
  EXPECT_TRUE(throwsNaming(pixels, 1, 1, spec, params, "PhotometryParams.camera_blur_sigma"));
  io::PatternSetSpec bad_spec;
  bad_spec.phase_period = 2;
  EXPECT_TRUE(throwsNaming(pixels, 1, 1, bad_spec, noiseless(), "PatternSetSpec.phase_period"));
}

}  // namespace
}  // namespace binpick::simulation
