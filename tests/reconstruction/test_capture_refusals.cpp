// Captures whose images or calibration lie about what they show: each is refused with a message
// naming the culprit, and the same captures untouched pass, in clean and in harsh light.
#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "binpick/core/error.hpp"
#include "binpick/reconstruction/decoder.hpp"
#include "binpick/reconstruction/reconstruction.hpp"
#include "thrown_message.hpp"
#include "virtual_capture.hpp"

namespace binpick::reconstruction {
namespace {

// Image indices in a 1280x800 set with row codes and four phase steps: white, black, 11 column
// (pattern, inverse) pairs, 4 column phase steps, 10 row pairs, 4 row phase steps.
constexpr int kGrayCol03 = 2 + 2 * 3;
constexpr int kFirstColumnPhase = 2 + 2 * 11;
constexpr int kGrayRow02 = kFirstColumnPhase + 4 + 2 * 2;

testing::CaptureOptions smallOptions(const std::string& lighting = "clean") {
  testing::CaptureOptions options;
  options.camera_scale = 0.5;
  options.lighting = lighting;
  return options;
}

io::Capture smallCapture(const std::string& lighting = "clean") {
  return testing::deepCopy(testing::virtualCapture(smallOptions(lighting)).capture);
}

std::string decodeError(const io::Capture& capture) {
  return binpick::test::thrownMessage([&] { decodeCapture(capture); });
}

TEST(CaptureRefusals, UntouchedCapturesPassInCleanAndHarshLight) {
  for (const std::string lighting : {"clean", "harsh"}) {
    EXPECT_EQ(decodeError(smallCapture(lighting)), "") << lighting;
  }
}

TEST(CaptureRefusals, Untouched16BitAndColumnOnlyCapturesPass) {
  testing::CaptureOptions deep = smallOptions("harsh");
  deep.bit_depth = 16;
  EXPECT_EQ(decodeError(testing::virtualCapture(deep).capture), "");
  testing::CaptureOptions columns = smallOptions("harsh");
  columns.row_codes = false;
  EXPECT_EQ(decodeError(testing::virtualCapture(columns).capture), "");
}

TEST(CaptureRefusals, NamesAGrayPatternSwappedWithItsInverse) {
  for (const std::string lighting : {"clean", "harsh"}) {
    io::Capture capture = smallCapture(lighting);
    std::swap(capture.images[kGrayCol03], capture.images[kGrayCol03 + 1]);
    const std::string message = decodeError(capture);
    EXPECT_NE(message.find("images 008_gray_col_03 and 009_gray_col_03_inv are swapped (pattern and inverse)"),
              std::string::npos)
        << lighting << ": " << message;
  }
  io::Capture rows = smallCapture();
  std::swap(rows.images[kGrayRow02], rows.images[kGrayRow02 + 1]);
  EXPECT_NE(decodeError(rows).find("gray_row_02_inv are swapped"), std::string::npos) << decodeError(rows);
}

TEST(CaptureRefusals, NamesTheMostSignificantGrayPatternSwapped) {
  io::Capture capture = smallCapture();
  std::swap(capture.images[2], capture.images[3]);
  EXPECT_NE(decodeError(capture).find("002_gray_col_00 and 003_gray_col_00_inv are swapped"), std::string::npos)
      << decodeError(capture);
}

TEST(CaptureRefusals, NamesPhaseStepsOutOfOrder) {
  for (const std::string lighting : {"clean", "harsh"}) {
    io::Capture capture = smallCapture(lighting);
    std::swap(capture.images[kFirstColumnPhase + 1], capture.images[kFirstColumnPhase + 3]);
    const std::string message = decodeError(capture);
    EXPECT_NE(message.find("column phase steps out of order (step 1 and step 3 swapped?"), std::string::npos)
        << lighting << ": " << message;
  }
}

TEST(CaptureRefusals, RefusesAPatternSetForAnotherProjector) {
  const testing::VirtualCapture& v = testing::virtualCapture(smallOptions());
  io::RigCalibration other = v.scene.rig;
  other.projector = other.projector.scaled(0.8);  // 1024 x 640
  const std::string message = binpick::test::thrownMessage([&] { Reconstructor(other).reconstruct(v.capture); });
  EXPECT_NE(message.find("pattern set is for a 1280x800 projector but the calibration's projector is 1024x640"),
            std::string::npos)
      << message;
}

TEST(CaptureRefusals, WarnsOfABaselineAlongTheCodedColumns) {
  testing::CaptureOptions options = smallOptions();
  options.row_codes = false;
  const testing::VirtualCapture& v = testing::virtualCapture(options);
  EXPECT_TRUE(Reconstructor(v.scene.rig).reconstruct(v.capture).warnings.empty());
  io::RigCalibration vertical = v.scene.rig;
  const Eigen::Vector3d t = vertical.T_projector_camera.translation();
  vertical.T_projector_camera.translation() = Eigen::Vector3d(0.1 * t.x(), t.norm(), t.z());
  const Reconstruction result = Reconstructor(vertical).reconstruct(v.capture);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_NE(result.warnings[0].find("baseline nearly along the projector's columns"), std::string::npos)
      << result.warnings[0];
  // With rows coded, the row carries the depth: no warning.
  const testing::VirtualCapture& coded = testing::virtualCapture(smallOptions());
  EXPECT_TRUE(Reconstructor(vertical).reconstruct(coded.capture).warnings.empty());
}

}  // namespace
}  // namespace binpick::reconstruction
