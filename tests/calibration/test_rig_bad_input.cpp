// Bad input to the camera + projector calibration: each refused with an error, or left out with
// a warning, that names the view and says what was wrong.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "binpick/calibration/rig_calibrator.hpp"
#include "rig_test_data.hpp"
#include "temp_directory_test.hpp"
#include "thrown_message.hpp"

namespace binpick::calibration {
namespace {

using test::readTestViews;
using test::rigTestData;

// Below the hard minimum of three (the default), or the min_views asked for, an error.
TEST(RigCalibrationBadInput, TooFewUsableViewsIsAnErrorNamingTheUnusableOnes) {
  const test::RigTestData& data = rigTestData();
  const std::vector<RigView> views = readTestViews({data.views[0], data.no_board, data.views[1]});
  const std::string message = test::thrownMessage([&] { calibrateRig(views, data.layout); });
  EXPECT_NE(message.find("2 usable views of 3, at least 3 needed"), std::string::npos) << message;
  EXPECT_NE(message.find(data.no_board + " (board not found"), std::string::npos) << message;
  EXPECT_EQ(message.find(data.views[1]), std::string::npos) << message;

  std::vector<RigView> four = views;
  four.push_back(readTestViews({data.views[2]}).front());
  RigCalibrationParams params;
  params.min_views = 8;
  const std::string eight = test::thrownMessage([&] { calibrateRig(four, data.layout, params); });
  EXPECT_NE(eight.find("3 usable views of 4, at least 8 needed"), std::string::npos) << eight;
}

TEST(RigCalibrationBadInput, ACaptureWithoutRowCodesIsRefusedNamingIt) {
  const test::RigTestData& data = rigTestData();
  const std::string message = test::thrownMessage([&] { readRigView(data.no_rows, data.layout); });
  EXPECT_EQ(message.rfind(data.no_rows + ": the capture has no row codes", 0), 0u) << message;
}

using RigCalibrationBadFiles = test::TempDirectoryTest;

TEST_F(RigCalibrationBadFiles, ACorruptCaptureIsRefusedNamingIt) {
  const test::RigTestData& data = rigTestData();
  const std::string garbage = pathOf("garbage");
  std::filesystem::create_directories(garbage);
  std::ofstream(garbage + "/capture.json") << "{\"format_version\": 1, \"source\": ";
  EXPECT_TRUE(test::throwsNaming([&] { readRigView(garbage, data.layout); }, garbage));

  const std::string missing = pathOf("missing_image");
  std::filesystem::copy(data.views[0], missing, std::filesystem::copy_options::recursive);
  std::filesystem::remove(missing + "/images/010_gray_col_04.png");
  EXPECT_TRUE(test::throwsNaming([&] { readRigView(missing, data.layout); }, missing));

  EXPECT_TRUE(test::throwsNaming([&] { readRigView(pathOf("nothing_here"), data.layout); }, pathOf("nothing_here")));
}

TEST(RigCalibrationBadInput, ViewsOfAnotherRigAreRefusedNamingThem) {
  const test::RigTestData& data = rigTestData();
  std::vector<RigView> views = readTestViews({data.views[0], data.views[1], data.views[2]});
  views[2].name = "other_rig";
  views[2].projector_width = 1920;
  RigCalibrationParams params;
  params.min_views = 3;
  EXPECT_TRUE(test::throwsNaming([&] { calibrateRig(views, data.layout, params); },
                                 "other_rig: camera 640x512, projector 1920x800"));
}

TEST(RigCalibrationBadInput, BadParamsAreNamed) {
  const auto fails = [](auto change, const std::string& text) {
    RigCalibrationParams params;
    change(params);
    return test::throwsNaming([&] { calibrateRig({}, BoardLayout{}, params); }, text);
  };
  using P = RigCalibrationParams;
  EXPECT_TRUE(fails([](P& p) { p.min_views = 2; }, "RigCalibrationParams.min_views must be >= 3"));
  EXPECT_TRUE(fails([](P& p) { p.min_corners = 0; }, "RigCalibrationParams.min_corners"));
  EXPECT_TRUE(fails([](P& p) { p.outlier_factor = 0.5; }, "RigCalibrationParams.outlier_factor"));
  EXPECT_TRUE(fails([](P& p) { p.outlier_floor_px = -1.0; }, "RigCalibrationParams.outlier_floor_px"));
  EXPECT_TRUE(fails([](P& p) { p.warn_rms_px = 0.0; }, "RigCalibrationParams.warn_rms_px"));

  RigViewParams view_params;
  view_params.projector.half_window = 0;
  EXPECT_TRUE(test::throwsNaming([&] { measureRigView(io::Capture{}, "v", BoardLayout{}, view_params); },
                                 "RigViewParams.projector: ProjectorCornerParams.half_window"));
}

}  // namespace
}  // namespace binpick::calibration
