// The projected pattern sequence: order and names, the Gray code, phase patterns and images.
#include "binpick/reconstruction/pattern_set.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bitset>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "binpick/core/error.hpp"
#include "thrown_message.hpp"

namespace binpick::reconstruction {
namespace {

constexpr double kPi = 3.14159265358979323846;

io::PatternSetSpec defaultSpec() { return io::PatternSetSpec{}; }  // 1280 x 800, both axes, 4 steps

std::vector<std::string> expectedNames(const char* axis, int bits, int steps) {
  std::vector<std::string> names;
  for (int b = 0; b < bits; ++b) {
    char text[32];
    std::snprintf(text, sizeof text, "gray_%s_%02d", axis, b);
    names.push_back(text);
    names.push_back(std::string(text) + "_inv");
  }
  for (int k = 0; k < steps; ++k) names.push_back("phase_" + std::string(axis) + "_" + std::to_string(k));
  return names;
}

// The column (or row) spelled by the Gray bits of `coordinate` as the patterns show them.
unsigned decodeFromPatterns(PatternAxis axis, const io::PatternSetSpec& spec, int coordinate) {
  unsigned code = 0;
  int bits = 0;
  for (const Pattern& p : patternSequence(spec)) {
    if (p.axis != axis || p.kind != PatternKind::GrayBit) continue;
    EXPECT_EQ(p.index, bits);  // most significant first, no gaps
    code = (code << 1) | (patternBrightness(p, spec, coordinate) > 0.5 ? 1u : 0u);
    ++bits;
  }
  return grayDecode(code);
}

::testing::AssertionResult rejectedNaming(const io::PatternSetSpec& spec, const std::string& field) {
  return binpick::test::throwsNaming([&] { patternSequence(spec); }, field);
}

TEST(PatternSet, DefaultSequenceHas52ImagesInTheDocumentedOrder) {
  const std::vector<std::string> names = patternNames(defaultSpec());
  std::vector<std::string> expected{"white", "black"};
  for (const auto& n : expectedNames("col", 11, 4)) expected.push_back(n);
  for (const auto& n : expectedNames("row", 10, 4)) expected.push_back(n);
  ASSERT_EQ(names.size(), 52u);
  EXPECT_EQ(names, expected);
  EXPECT_EQ(names[2], "gray_col_00");
  EXPECT_EQ(names[3], "gray_col_00_inv");
  EXPECT_EQ(names[24], "phase_col_0");
  EXPECT_EQ(names[51], "phase_row_3");
}

TEST(PatternSet, SequenceKindsMatchTheirNames) {
  const std::vector<Pattern> sequence = patternSequence(defaultSpec());
  const std::vector<std::string> names = patternNames(defaultSpec());
  ASSERT_EQ(sequence.size(), names.size());
  for (std::size_t i = 0; i < sequence.size(); ++i) EXPECT_EQ(sequence[i].name(), names[i]);
  EXPECT_EQ(sequence[0].kind, PatternKind::White);
  EXPECT_EQ(sequence[1].kind, PatternKind::Black);
  EXPECT_EQ(sequence[2].kind, PatternKind::GrayBit);
  EXPECT_EQ(sequence[2].axis, PatternAxis::Columns);
  EXPECT_EQ(sequence[3].kind, PatternKind::GrayBitInverse);
  EXPECT_EQ(sequence[27].kind, PatternKind::PhaseStep);
  EXPECT_EQ(sequence[27].index, 3);
  EXPECT_EQ(sequence[28].axis, PatternAxis::Rows);
}

TEST(PatternSet, AxesAndPhaseStepsCanBeSwitchedOff) {
  io::PatternSetSpec spec = defaultSpec();
  spec.row_codes = false;
  std::vector<std::string> expected{"white", "black"};
  for (const auto& n : expectedNames("col", 11, 4)) expected.push_back(n);
  EXPECT_EQ(patternNames(spec), expected);

  spec = defaultSpec();
  spec.column_codes = false;
  spec.phase_steps = 0;
  expected = {"white", "black"};
  for (const auto& n : expectedNames("row", 10, 0)) expected.push_back(n);
  EXPECT_EQ(patternNames(spec), expected);

  spec = defaultSpec();
  spec.phase_steps = 3;
  EXPECT_EQ(patternNames(spec).size(), 2u + 22u + 3u + 20u + 3u);
}

TEST(PatternSet, GrayCodeBitsIsCeilLog2) {
  EXPECT_EQ(grayCodeBits(2), 1);
  EXPECT_EQ(grayCodeBits(3), 2);
  EXPECT_EQ(grayCodeBits(4), 2);
  EXPECT_EQ(grayCodeBits(5), 3);
  EXPECT_EQ(grayCodeBits(800), 10);
  EXPECT_EQ(grayCodeBits(912), 10);
  EXPECT_EQ(grayCodeBits(1024), 10);
  EXPECT_EQ(grayCodeBits(1025), 11);
  EXPECT_EQ(grayCodeBits(1280), 11);
  EXPECT_EQ(grayCodeBits(65536), 16);
}

TEST(PatternSet, GrayDecodeInvertsGrayCode) {
  for (unsigned i = 0; i < (1u << 16); ++i) ASSERT_EQ(grayDecode(grayCode(i)), i);
  for (unsigned i : {0xFFFFFFFFu, 0x80000000u, 0xDEADBEEFu, 0x12345678u}) {
    EXPECT_EQ(grayDecode(grayCode(i)), i);
  }
}

TEST(PatternSet, AdjacentCodesDifferInExactlyOneBit) {
  for (unsigned i = 0; i + 1 < (1u << 16); ++i) {
    ASSERT_EQ(std::bitset<32>(grayCode(i) ^ grayCode(i + 1)).count(), 1u) << i;
  }
}

TEST(PatternSet, GrayBitsDecodeToTheirColumnAndRow) {
  for (int width : {1280, 912}) {
    io::PatternSetSpec spec = defaultSpec();
    spec.projector_width = width;
    spec.projector_height = width == 912 ? 1140 : 800;
    for (int c = 0; c < spec.projector_width; ++c) {
      ASSERT_EQ(decodeFromPatterns(PatternAxis::Columns, spec, c), static_cast<unsigned>(c)) << "width " << width;
    }
    for (int r = 0; r < spec.projector_height; ++r) {
      ASSERT_EQ(decodeFromPatterns(PatternAxis::Rows, spec, r), static_cast<unsigned>(r))
          << "height " << spec.projector_height;
    }
  }
}

TEST(PatternSet, MostSignificantColumnBitSplitsAtAPowerOfTwo) {
  // For 1280 columns (11 bits) the first bit is on from column 1024 on.
  const io::PatternSetSpec spec = defaultSpec();
  const Pattern msb{PatternKind::GrayBit, PatternAxis::Columns, 0};
  EXPECT_EQ(patternBrightness(msb, spec, 1023), 0.0);
  EXPECT_EQ(patternBrightness(msb, spec, 1024), 1.0);
  EXPECT_EQ(patternBrightness(msb, spec, 1279), 1.0);
}

TEST(PatternSet, EachInverseIsTheComplement) {
  const io::PatternSetSpec spec = defaultSpec();
  for (const Pattern& p : patternSequence(spec)) {
    if (p.kind != PatternKind::GrayBit) continue;
    const Pattern inverse{PatternKind::GrayBitInverse, p.axis, p.index};
    const int size = p.axis == PatternAxis::Columns ? spec.projector_width : spec.projector_height;
    for (int c = 0; c < size; ++c) {
      const double b = patternBrightness(p, spec, c);
      ASSERT_TRUE(b == 0.0 || b == 1.0);
      ASSERT_EQ(patternBrightness(inverse, spec, c), 1.0 - b) << p.name() << " at " << c;
    }
  }
}

TEST(PatternSet, WhiteAndBlackAreUniform) {
  const io::PatternSetSpec spec = defaultSpec();
  const Pattern white{PatternKind::White, PatternAxis::None, 0};
  const Pattern black{PatternKind::Black, PatternAxis::None, 0};
  for (int c : {0, 17, 1279}) {
    EXPECT_EQ(patternBrightness(white, spec, c), 1.0);
    EXPECT_EQ(patternBrightness(black, spec, c), 0.0);
  }
}

TEST(PatternSet, PhaseStepsEncodeThePhaseOfEachColumn) {
  for (int steps : {3, 4, 7}) {
    io::PatternSetSpec spec = defaultSpec();
    spec.phase_steps = steps;
    spec.phase_period = 20;
    double worst = 0.0;
    for (int c = 0; c < spec.projector_width; ++c) {
      // First Fourier coefficient over the steps: I_k = A + B cos(phi - 2 pi k / N).
      double s = 0.0, k_cos = 0.0;
      for (int k = 0; k < steps; ++k) {
        const double b = patternBrightness({PatternKind::PhaseStep, PatternAxis::Columns, k}, spec, c);
        ASSERT_GE(b, 0.0);
        ASSERT_LE(b, 1.0);
        // An 8-bit projector level.
        ASSERT_NEAR(b * 255.0, std::round(b * 255.0), 1e-9);
        s += b * std::sin(2.0 * kPi * k / steps);
        k_cos += b * std::cos(2.0 * kPi * k / steps);
      }
      const double phase = std::atan2(s, k_cos);
      const double expected = 2.0 * kPi * c / spec.phase_period;
      const double error = std::remainder(phase - expected, 2.0 * kPi);
      worst = std::max(worst, std::abs(error));
    }
    EXPECT_LT(worst, 0.01) << steps << " steps";
  }
}

TEST(PatternSet, RowPhaseFollowsTheRow) {
  const io::PatternSetSpec spec = defaultSpec();  // period 16, 4 steps
  // Row 4 is a quarter period: phase pi/2, so step 1 (shift pi/2) is at its brightest.
  EXPECT_EQ(patternBrightness({PatternKind::PhaseStep, PatternAxis::Rows, 1}, spec, 4), 1.0);
  EXPECT_EQ(patternBrightness({PatternKind::PhaseStep, PatternAxis::Rows, 3}, spec, 4), 0.0);
  // Columns do not matter to a row pattern.
  EXPECT_EQ(patternImage({PatternKind::PhaseStep, PatternAxis::Rows, 1}, spec).at<uchar>(4, 333), 255);
}

TEST(PatternSet, ImagesHaveTheProjectorSizeAndFollowPatternBrightness) {
  io::PatternSetSpec spec = defaultSpec();
  spec.projector_width = 96;
  spec.projector_height = 40;
  spec.phase_period = 12;
  for (const Pattern& p : patternSequence(spec)) {
    const cv::Mat image = patternImage(p, spec);
    ASSERT_EQ(image.type(), CV_8UC1);
    ASSERT_EQ(image.cols, 96);
    ASSERT_EQ(image.rows, 40);
    for (int row = 0; row < image.rows; ++row) {
      for (int col = 0; col < image.cols; ++col) {
        const int coordinate = p.axis == PatternAxis::Rows ? row : col;
        const double expected = 255.0 * patternBrightness(p, spec, coordinate);
        ASSERT_EQ(image.at<uchar>(row, col), static_cast<int>(std::lround(expected)))
            << p.name() << " at (" << col << ", " << row << ")";
      }
    }
  }
}

TEST(PatternSet, ColumnPatternsAreConstantDownEachColumn) {
  const io::PatternSetSpec spec = defaultSpec();
  const cv::Mat image = patternImage({PatternKind::GrayBit, PatternAxis::Columns, 10}, spec);
  ASSERT_EQ(image.size(), cv::Size(1280, 800));
  cv::Mat first_row;
  cv::repeat(image.row(0), image.rows, 1, first_row);
  EXPECT_EQ(cv::norm(image, first_row, cv::NORM_INF), 0.0);
  // The least significant bit of a Gray code runs in stripes two columns wide: 0 1 1 0 0 1 1 0.
  const std::vector<int> expected{0, 255, 255, 0, 0, 255, 255, 0};
  for (int c = 0; c < 8; ++c) EXPECT_EQ(image.at<uchar>(5, c), expected[c]) << c;
}

TEST(PatternSet, BadSpecsAreRejectedNamingTheField) {
  io::PatternSetSpec spec = defaultSpec();
  spec.projector_width = 1;
  EXPECT_TRUE(rejectedNaming(spec, "projector_width"));
  spec = defaultSpec();
  spec.projector_height = 70000;
  EXPECT_TRUE(rejectedNaming(spec, "projector_height"));
  spec = defaultSpec();
  spec.phase_steps = 2;
  EXPECT_TRUE(rejectedNaming(spec, "phase_steps"));
  spec = defaultSpec();
  spec.phase_steps = -1;
  EXPECT_TRUE(rejectedNaming(spec, "phase_steps"));
  spec = defaultSpec();
  spec.phase_period = 3;
  EXPECT_TRUE(rejectedNaming(spec, "phase_period"));
  spec = defaultSpec();
  spec.column_codes = false;
  spec.row_codes = false;
  EXPECT_TRUE(rejectedNaming(spec, "column_codes"));
  EXPECT_THROW(patternImage({PatternKind::White, PatternAxis::None, 0}, spec), core::Error);
  for (const auto& [unit, steps] : {std::pair{24, 4}, std::pair{8, 0}, std::pair{-2, 4}}) {
    spec = defaultSpec();  // a period of 16
    spec.gray_unit = unit;
    spec.phase_steps = steps;
    EXPECT_TRUE(rejectedNaming(spec, "gray_unit")) << unit << " with " << steps << " phase steps";
  }
}

// Words of half a period (a complementary Gray code): each bit is the full code's bit three
// places lower, so a column's word is its column divided by 8.
TEST(PatternSet, GrayWordsCountUnitsOfColumns) {
  io::PatternSetSpec spec = defaultSpec();  // 1280 x 800, a period of 16
  spec.gray_unit = 8;
  EXPECT_EQ(patternSequence(spec).size(), 2u + (8 * 2 + 4) + (7 * 2 + 4));
  io::PatternSetSpec full = defaultSpec();
  for (int bit = 0; bit < 8; ++bit) {
    for (const int column : {0, 7, 8, 15, 100, 1279}) {
      EXPECT_EQ(patternBrightness({PatternKind::GrayBit, PatternAxis::Columns, bit}, spec, column),
                patternBrightness({PatternKind::GrayBit, PatternAxis::Columns, bit}, full, column))
          << "bit " << bit << ", column " << column;
    }
  }
}

}  // namespace
}  // namespace binpick::reconstruction
