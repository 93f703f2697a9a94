// binpickd's hand_eye section: the result file of `binpick calibrate hand-eye` by path, as an
// alternative to a pose written in place, and every mistake named.
#include <gtest/gtest.h>

#include <fstream>

#include "binpick/calibration/hand_eye_file.hpp"
#include "binpick/cell/cell_config.hpp"
#include "temp_directory_test.hpp"
#include "thrown_message.hpp"

namespace binpick::cell {
namespace {

using test::throwsNaming;

const std::string kMinimal =
    "source: {replay: {path: captures}}\n"
    "recipes: [{name: part, model: part.ply, grasps: [{translation: [0, 0, 0.01]}]}]\n";

class HandEyeConfig : public test::TempDirectoryTest {
 protected:
  // A calibration as `binpick calibrate hand-eye` writes it.
  calibration::HandEyeFile result(calibration::HandEyeSetup setup) const {
    calibration::HandEyeFile file;
    file.setup = setup;
    file.T_mount_camera.linear() = Eigen::AngleAxisd(3.0, Eigen::Vector3d(0.1, 1.0, 0.05).normalized()).matrix();
    file.T_mount_camera.translation() = Eigen::Vector3d(0.61, -0.02, 0.93);
    file.method = "shah";
    file.date = "2026-01-31T12:00:00.000Z";
    file.views = 12;
    return file;
  }
  CellConfig parse(const std::string& hand_eye) const {
    return parseCellConfig(kMinimal + hand_eye, "cell.yaml", root());
  }
};

TEST_F(HandEyeConfig, TheResultFileIsReadRelativeToTheSettings) {
  const calibration::HandEyeFile file = result(calibration::HandEyeSetup::EyeToHand);
  calibration::writeHandEyeFile(pathOf("calib/hand_eye.yaml"), file);
  const CellConfig config = parse("hand_eye: {file: calib/hand_eye.yaml}\n");
  ASSERT_TRUE(config.T_base_camera.has_value());
  EXPECT_LT((config.T_base_camera->matrix() - file.T_mount_camera.matrix()).norm(), 1e-9);
}

TEST_F(HandEyeConfig, TheResultsSectionPastedInPlaceReadsToo) {
  calibration::writeHandEyeFile(pathOf("hand_eye.yaml"), result(calibration::HandEyeSetup::EyeToHand));
  std::ifstream in(pathOf("hand_eye.yaml"));
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const CellConfig config = parseCellConfig(text + kMinimal, "cell.yaml", root());
  ASSERT_TRUE(config.T_base_camera.has_value());
  EXPECT_NEAR(config.T_base_camera->translation().z(), 0.93, 1e-12);
}

TEST_F(HandEyeConfig, MistakesAreNamed) {
  calibration::writeHandEyeFile(pathOf("eye_in_hand.yaml"), result(calibration::HandEyeSetup::EyeInHand));
  EXPECT_TRUE(throwsNaming([&] { parse("hand_eye: {file: h.yaml, T_base_camera: {translation: [0, 0, 1]}}\n"); },
                           "cell.yaml: hand_eye.file and hand_eye.T_base_camera are both given"));
  EXPECT_TRUE(throwsNaming([&] { parse("hand_eye: {file: missing.yaml}\n"); },
                           "cell.yaml: hand_eye.file: " + pathOf("missing.yaml") + ": cannot open"));
  EXPECT_TRUE(throwsNaming([&] { parse("hand_eye: {file: eye_in_hand.yaml}\n"); },
                           "eye-in-hand calibration (T_flange_camera)"));
  std::ofstream(pathOf("typo.yaml")) << "hand_eye:\n  T_base_camera: {translation: [0, 0, 1]}\n  detials: {}\n";
  EXPECT_TRUE(throwsNaming([&] { parse("hand_eye: {file: typo.yaml}\n"); },
                           "typo.yaml: hand_eye.detials is not a known setting"));
}

}  // namespace
}  // namespace binpick::cell
