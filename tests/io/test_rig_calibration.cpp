// calib.yaml: RigCalibration written and read through OpenCV FileStorage, every key checked.
#include "binpick/io/rig_calibration.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/eigen.hpp>
#include <optional>
#include <string>

#include "binpick/core/error.hpp"
#include "io_test_support.hpp"

namespace binpick::test {
namespace {

using RigCalibrationTest = IoTest;

// Writes `value` under `key`, or nothing: how a test replaces or drops one key of a file.
using KeyWriter = std::function<void(cv::FileStorage&, const std::string& key)>;

io::RigCalibration sampleRig() {
  io::RigCalibration rig;
  rig.camera.width = 1280;
  rig.camera.height = 1024;
  rig.camera.fx = 1603.123456789012;
  rig.camera.fy = 1601.987654321098;
  rig.camera.cx = 641.3000000000001;
  rig.camera.cy = 509.8123456789;
  rig.camera.distortion = {-0.0812345678901234, 0.1211111111111, 4.00000001e-4, -3.3e-4, -0.0123456789};
  rig.projector.width = 1280;
  rig.projector.height = 800;
  rig.projector.fx = 1450.5;
  rig.projector.fy = 1449.25;
  rig.projector.cx = 639.5;
  rig.projector.cy = 799.125;  // projectors usually have their axis at the image's edge
  rig.projector.distortion = {0.021, -0.043, 0.0, 1e-17, 0.0};
  rig.T_projector_camera.linear() =
      Eigen::AngleAxisd(0.2617993877991494, Eigen::Vector3d(0.1, 0.98, -0.05).normalized()).toRotationMatrix();
  rig.T_projector_camera.translation() = Eigen::Vector3d(-0.2134567890123, 0.0123, 0.0456789);
  return rig;
}

cv::Mat openCvCameraMatrix(const io::LensIntrinsics& lens) {
  return (cv::Mat_<double>(3, 3) << lens.fx, 0, lens.cx, 0, lens.fy, lens.cy, 0, 0, 1);
}

// The sample rig as a user's own cv::FileStorage code would write it: the camera matrix and
// distortion as calibrateCamera returns them (3x3, 1x5), the projector's distortion as a column
// with four values, R as cv::Rodrigues gives it and T as a 3x1 column. `replace` swaps or drops
// single keys.
void writeWithOpenCv(const std::string& path, const std::map<std::string, KeyWriter>& replace = {}) {
  const io::RigCalibration rig = sampleRig();
  cv::Mat r;
  cv::eigen2cv(Eigen::Matrix3d(rig.T_projector_camera.linear()), r);
  cv::Mat rvec;
  cv::Rodrigues(r, rvec);
  cv::Rodrigues(rvec, r);
  const cv::Mat t = (cv::Mat_<double>(3, 1) << rig.T_projector_camera.translation().x(),
                     rig.T_projector_camera.translation().y(), rig.T_projector_camera.translation().z());
  const std::map<std::string, KeyWriter> standard{
      {"camera_width", [&](cv::FileStorage& fs, const std::string& k) { fs << k << 1280; }},
      {"camera_height", [&](cv::FileStorage& fs, const std::string& k) { fs << k << 1024; }},
      {"camera_matrix", [&](cv::FileStorage& fs, const std::string& k) { fs << k << openCvCameraMatrix(rig.camera); }},
      {"camera_distortion",
       [&](cv::FileStorage& fs, const std::string& k) {
         fs << k << cv::Mat(1, 5, CV_64F, const_cast<double*>(rig.camera.distortion.data()));
       }},
      {"projector_width", [&](cv::FileStorage& fs, const std::string& k) { fs << k << 1280; }},
      {"projector_height", [&](cv::FileStorage& fs, const std::string& k) { fs << k << 800; }},
      {"projector_matrix",
       [&](cv::FileStorage& fs, const std::string& k) { fs << k << openCvCameraMatrix(rig.projector); }},
      {"projector_distortion",
       [&](cv::FileStorage& fs, const std::string& k) {
         fs << k << (cv::Mat_<double>(4, 1) << 0.021, -0.043, 0.0, 1e-17);
       }},
      {"R", [&](cv::FileStorage& fs, const std::string& k) { fs << k << r; }},
      {"T", [&](cv::FileStorage& fs, const std::string& k) { fs << k << t; }},
  };
  cv::FileStorage fs(path, cv::FileStorage::WRITE | cv::FileStorage::FORMAT_YAML);
  ASSERT_TRUE(fs.isOpened());
  for (const char* key : {"camera_width", "camera_height", "camera_matrix", "camera_distortion", "projector_width",
                          "projector_height", "projector_matrix", "projector_distortion", "R", "T"}) {
    const auto it = replace.find(key);
    (it != replace.end() ? it->second : standard.at(key))(fs, key);
  }
}

KeyWriter dropKey() {
  return [](cv::FileStorage&, const std::string&) {};
}

KeyWriter writeMat(cv::Mat value) {
  return [value](cv::FileStorage& fs, const std::string& key) { fs << key << value; };
}

void expectSameLens(const io::LensIntrinsics& a, const io::LensIntrinsics& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_NEAR(a.fx, b.fx, 1e-12);
  EXPECT_NEAR(a.fy, b.fy, 1e-12);
  EXPECT_NEAR(a.cx, b.cx, 1e-12);
  EXPECT_NEAR(a.cy, b.cy, 1e-12);
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(a.distortion[i], b.distortion[i], 1e-12) << "k" << i;
}

TEST_F(RigCalibrationTest, WriteThenReadGivesTheSameRig) {
  const io::RigCalibration rig = sampleRig();
  const std::string path = pathOf("calib.yaml");
  io::writeRigCalibration(path, rig);
  const io::RigCalibration back = io::readRigCalibration(path);
  expectSameLens(back.camera, rig.camera);
  expectSameLens(back.projector, rig.projector);
  EXPECT_LT((back.T_projector_camera.matrix() - rig.T_projector_camera.matrix()).cwiseAbs().maxCoeff(), 1e-12);
  // Written through a temporary file that is renamed: nothing else is left beside it.
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(path).parent_path())) {
    EXPECT_EQ(entry.path().filename(), "calib.yaml");
  }
}

// A calibration's quality as `binpick calibrate rig` writes it: one used view, one dropped
// outlier, and one never calibrated (its RMS unknown), with names and problems that need quoting.
io::RigCalibrationQuality sampleQuality() {
  io::RigCalibrationQuality quality;
  quality.date = "2026-01-31T12:00:00.123Z";
  quality.camera_rms_px = 0.0891234567890123;
  quality.projector_rms_px = 0.165;
  quality.stereo_rms_px = 0.134;
  io::RigViewQuality used;
  used.name = "views/pose 000";
  used.camera_corners = 48;
  used.projector_corners = 47;
  used.camera_rms_px = 0.12;
  used.projector_rms_px = 0.21;
  used.used = true;
  io::RigViewQuality dropped = used;
  dropped.name = "views/pose_001";
  dropped.camera_rms_px = 2.5;
  dropped.outlier = true;
  dropped.used = false;
  dropped.problem = "outlier, dropped";
  io::RigViewQuality missing;
  missing.name = "views/no_board";
  missing.problem = "board not found: no ArUco marker of DICT_5X5_100 in the image";
  quality.views = {used, dropped, missing};
  return quality;
}

void expectSameView(const io::RigViewQuality& a, const io::RigViewQuality& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.camera_corners, b.camera_corners);
  EXPECT_EQ(a.projector_corners, b.projector_corners);
  // NaN (never calibrated) must come back as NaN.
  const auto same = [](double x, double y) { return std::isnan(x) ? std::isnan(y) : x == y; };
  EXPECT_PRED2(same, a.camera_rms_px, b.camera_rms_px);
  EXPECT_PRED2(same, a.projector_rms_px, b.projector_rms_px);
  EXPECT_EQ(a.outlier, b.outlier);
  EXPECT_EQ(a.used, b.used);
  EXPECT_EQ(a.problem, b.problem);
}

TEST_F(RigCalibrationTest, QualityIsWrittenBesideTheRigAndReadsBack) {
  const std::string path = pathOf("calib.yaml");
  io::writeRigCalibration(path, sampleRig(), sampleQuality());
  // The rig reads as from any other file.
  const io::RigCalibration rig = io::readRigCalibration(path);
  expectSameLens(rig.camera, sampleRig().camera);
  EXPECT_LT((rig.T_projector_camera.matrix() - sampleRig().T_projector_camera.matrix()).cwiseAbs().maxCoeff(), 1e-12);
  const std::optional<io::RigCalibrationQuality> quality = io::readRigCalibrationQuality(path);
  ASSERT_TRUE(quality.has_value());
  const io::RigCalibrationQuality expected = sampleQuality();
  EXPECT_EQ(quality->date, expected.date);
  EXPECT_DOUBLE_EQ(quality->camera_rms_px, expected.camera_rms_px);
  EXPECT_DOUBLE_EQ(quality->projector_rms_px, expected.projector_rms_px);
  EXPECT_DOUBLE_EQ(quality->stereo_rms_px, expected.stereo_rms_px);
  ASSERT_EQ(quality->views.size(), expected.views.size());
  for (std::size_t i = 0; i < expected.views.size(); ++i) {
    SCOPED_TRACE(expected.views[i].name);
    expectSameView(quality->views[i], expected.views[i]);
  }
  EXPECT_EQ(quality->viewsUsed(), 1);
  // The counts a reader of the file sees without summing the list.
  cv::FileStorage fs(path, cv::FileStorage::READ);
  EXPECT_EQ(static_cast<int>(fs["quality"]["views_used"]), 1);
  EXPECT_EQ(static_cast<int>(fs["quality"]["views_dropped"]), 2);
}

TEST_F(RigCalibrationTest, FilesWithoutQualityHaveNone) {
  const std::string path = pathOf("calib.yaml");
  io::writeRigCalibration(path, sampleRig());
  EXPECT_FALSE(io::readRigCalibrationQuality(path).has_value());
  writeWithOpenCv(path);
  EXPECT_FALSE(io::readRigCalibrationQuality(path).has_value());
}

TEST_F(RigCalibrationTest, MalformedQualityIsNamedAndDoesNotStopTheRig) {
  const std::string path = pathOf("calib.yaml");
  writeWithOpenCv(path);
  std::ofstream(path, std::ios::app) << "quality:\n   date: \"2026-01-31T12:00:00Z\"\n"
                                     << "   views:\n      - { name: a, camera_corners: many }\n";
  EXPECT_TRUE(failsWith([&] { io::readRigCalibrationQuality(path); }, path,
                        "quality.views[0].camera_corners must be an integer"));
  EXPECT_EQ(io::readRigCalibration(path).camera.width, 1280);
}

TEST_F(RigCalibrationTest, WriteReplacesAnExistingFile) {
  const std::string path = pathOf("calib.yaml");
  io::RigCalibration rig = sampleRig();
  io::writeRigCalibration(path, rig);
  rig.camera.fx = 1234.5;
  io::writeRigCalibration(path, rig);
  EXPECT_EQ(io::readRigCalibration(path).camera.fx, 1234.5);
}

TEST_F(RigCalibrationTest, WriteRejectsAnInvalidRigAndWritesNothing) {
  io::RigCalibration rig = sampleRig();
  rig.projector.fy = 0.0;
  const std::string path = pathOf("calib.yaml");
  EXPECT_THROW(io::writeRigCalibration(path, rig), core::Error);
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST_F(RigCalibrationTest, WriteIntoAMissingDirectoryIsAnError) {
  const std::string path = pathOf("no_such_directory/calib.yaml");
  EXPECT_THROW(io::writeRigCalibration(path, sampleRig()), core::Error);
}

TEST_F(RigCalibrationTest, ReadsAFileWrittenByPlainOpenCv) {
  const std::string path = pathOf("calib.yaml");
  writeWithOpenCv(path);
  const io::RigCalibration rig = io::readRigCalibration(path);
  const io::RigCalibration expected = sampleRig();
  expectSameLens(rig.camera, expected.camera);
  EXPECT_EQ(rig.projector.width, 1280);
  EXPECT_EQ(rig.projector.height, 800);
  EXPECT_EQ(rig.projector.distortion[3], 1e-17);
  EXPECT_EQ(rig.projector.distortion[4], 0.0);  // four coefficients: k3 = 0
  // R went through Rodrigues and back, so only to rounding.
  EXPECT_LT((rig.T_projector_camera.matrix() - expected.T_projector_camera.matrix()).cwiseAbs().maxCoeff(), 1e-12);
}

TEST_F(RigCalibrationTest, ReadsSinglePrecisionMatrices) {
  const std::string path = pathOf("calib.yaml");
  cv::Mat k32;
  openCvCameraMatrix(sampleRig().camera).convertTo(k32, CV_32F);
  writeWithOpenCv(path, {{"camera_matrix", writeMat(k32)}});
  EXPECT_NEAR(io::readRigCalibration(path).camera.fx, sampleRig().camera.fx, 1e-3);
}

TEST_F(RigCalibrationTest, ReadsTheDocumentedHandWrittenLayout) {
  const std::string path = writeFile("calib.yaml", R"(%YAML:1.0
---
camera_width: 1280
camera_height: 1024
camera_matrix: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 1600., 0., 641.3, 0., 1600., 509.8, 0., 0., 1. ]
camera_distortion: !!opencv-matrix
   rows: 1
   cols: 5
   dt: d
   data: [ -0.08, 0.12, 4.0e-04, -3.0e-04, 0. ]
projector_width: 1280
projector_height: 800
projector_matrix: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 1450., 0., 640., 0., 1450., 800., 0., 0., 1. ]
projector_distortion: !!opencv-matrix
   rows: 1
   cols: 4
   dt: d
   data: [ 0., 0., 0., 0. ]
R: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 0., 0., 1., 0., 1., 0., -1., 0., 0. ]
T: !!opencv-matrix
   rows: 3
   cols: 1
   dt: d
   data: [ -0.2, 0., 0.05 ]
)");
  const io::RigCalibration rig = io::readRigCalibration(path);
  EXPECT_EQ(rig.camera.cx, 641.3);
  EXPECT_EQ(rig.camera.distortion[2], 4e-4);
  EXPECT_EQ(rig.projector.cy, 800.0);
  EXPECT_EQ(rig.T_projector_camera.linear()(0, 2), 1.0);
  EXPECT_EQ(rig.T_projector_camera.linear()(2, 0), -1.0);
  EXPECT_EQ(rig.T_projector_camera.translation().z(), 0.05);
}

TEST_F(RigCalibrationTest, MissingFileIsAnError) {
  const std::string path = pathOf("nothing_here.yaml");
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "cannot open"));
}

TEST_F(RigCalibrationTest, GarbageIsAnErrorNotACrash) {
  const std::string not_yaml = "not an OpenCV FileStorage YAML file";
  const std::string binary = writeFile("binary.yaml", garbageBytes(3000, 7));
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(binary); }, binary, not_yaml));
  const std::string json = writeFile("json.yaml", "{\"camera_width\": [1, 2,\n");
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(json); }, json, not_yaml));
  const std::string text = writeFile("text.yaml", "this is not a calibration\n");
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(text); }, text, not_yaml));
  const std::string empty = writeFile("empty.yaml", "");
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(empty); }, empty, not_yaml));
  const std::string sequence = writeFile("sequence.yaml", "%YAML:1.0\n---\n- 1\n- 2\n");
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(sequence); }, sequence, not_yaml));
}

TEST_F(RigCalibrationTest, MalformedMatricesAreNamed) {
  const std::string path = pathOf("calib.yaml");
  const KeyWriter list = [](cv::FileStorage& fs, const std::string& k) { fs << k << "[" << 1 << 2 << 3 << "]"; };
  writeWithOpenCv(path, {{"camera_matrix", list}});
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "'camera_matrix'"));

  const KeyWriter no_data = [](cv::FileStorage& fs, const std::string& k) {
    fs << k << "{"
       << "rows" << 3 << "cols" << 1 << "dt"
       << "d"
       << "}";
  };
  writeWithOpenCv(path, {{"T", no_data}});
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "'T'"));

  const KeyWriter too_little_data = [](cv::FileStorage& fs, const std::string& k) {
    fs << k << "{"
       << "rows" << 3 << "cols" << 1 << "dt"
       << "d"
       << "data"
       << "[" << 1.0 << "]"
       << "}";
  };
  writeWithOpenCv(path, {{"T", too_little_data}});
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "'T'"));
}

TEST_F(RigCalibrationTest, NonYamlTextNamesTheProblem) {
  const std::string path = writeFile("calib.yaml", "\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR");
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "not an OpenCV FileStorage YAML"));
}

TEST_F(RigCalibrationTest, EachMissingKeyIsNamed) {
  for (const char* key : {"camera_width", "camera_height", "camera_matrix", "camera_distortion", "projector_width",
                          "projector_height", "projector_matrix", "projector_distortion", "R", "T"}) {
    SCOPED_TRACE(key);
    const std::string path = pathOf(std::string("no_") + key + ".yaml");
    writeWithOpenCv(path, {{key, dropKey()}});
    EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, std::string("missing key '") + key + "'"));
  }
}

TEST_F(RigCalibrationTest, WrongMatrixSizesAreNamed) {
  const std::string path = pathOf("calib.yaml");
  writeWithOpenCv(path, {{"camera_matrix", writeMat(cv::Mat::eye(2, 3, CV_64F) * 1000.0)}});
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "'camera_matrix' must be 3x3 (got 2x3)"));

  writeWithOpenCv(path, {{"R", writeMat(cv::Mat::eye(4, 4, CV_64F))}});
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "'R' must be 3x3 (got 4x4)"));

  writeWithOpenCv(path, {{"T", writeMat(cv::Mat::zeros(2, 1, CV_64F))}});
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "'T' must hold 3 values"));

  writeWithOpenCv(path, {{"T", writeMat(cv::Mat::zeros(3, 3, CV_64F))}});
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "'T' must hold 3 values"));
}

TEST_F(RigCalibrationTest, UnsupportedDistortionModelsAreRejected) {
  const std::string path = pathOf("calib.yaml");
  writeWithOpenCv(path, {{"camera_distortion", writeMat(cv::Mat::zeros(1, 8, CV_64F))}});
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "'camera_distortion' must hold 4 or 5 values"));
  writeWithOpenCv(path, {{"projector_distortion", writeMat(cv::Mat::zeros(2, 5, CV_64F))}});
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "'projector_distortion' must hold 4 or 5 values"));
}

TEST_F(RigCalibrationTest, CameraMatrixWithSkewIsRejected) {
  const std::string path = pathOf("calib.yaml");
  cv::Mat k = openCvCameraMatrix(sampleRig().camera);
  k.at<double>(0, 1) = 0.5;
  writeWithOpenCv(path, {{"camera_matrix", writeMat(k)}});
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "'camera_matrix' must be [fx 0 cx"));
}

TEST_F(RigCalibrationTest, NonRotationRIsRejected) {
  const std::string path = pathOf("calib.yaml");
  writeWithOpenCv(path, {{"R", writeMat(cv::Mat::eye(3, 3, CV_64F) * 1.01)}});
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "R must be a rotation"));

  const cv::Mat reflection = (cv::Mat_<double>(3, 3) << 1, 0, 0, 0, 1, 0, 0, 0, -1);
  writeWithOpenCv(path, {{"R", writeMat(reflection)}});
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "R must be a rotation"));
}

TEST_F(RigCalibrationTest, NonFiniteValuesAreRejected) {
  const std::string path = pathOf("calib.yaml");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  writeWithOpenCv(path, {{"T", writeMat((cv::Mat_<double>(3, 1) << 0.1, nan, 0.0))}});
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "'T' holds a non-finite value"));

  cv::Mat k = openCvCameraMatrix(sampleRig().projector);
  k.at<double>(0, 0) = std::numeric_limits<double>::infinity();
  writeWithOpenCv(path, {{"projector_matrix", writeMat(k)}});
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "'projector_matrix' holds a non-finite value"));
}

TEST_F(RigCalibrationTest, BadImageSizesAreNamed) {
  const std::string path = pathOf("calib.yaml");
  writeWithOpenCv(path, {{"camera_width", [](cv::FileStorage& fs, const std::string& k) { fs << k << -1280; }}});
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "camera.width must be in"));

  writeWithOpenCv(path, {{"projector_height", [](cv::FileStorage& fs, const std::string& k) { fs << k << 800.5; }}});
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "'projector_height' must be an integer"));

  writeWithOpenCv(path, {{"camera_height", [](cv::FileStorage& fs, const std::string& k) { fs << k << "1024"; }}});
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "'camera_height' must be an integer"));
}

TEST_F(RigCalibrationTest, ZeroFocalLengthIsNamed) {
  const std::string path = pathOf("calib.yaml");
  cv::Mat k = openCvCameraMatrix(sampleRig().projector);
  k.at<double>(1, 1) = 0.0;
  writeWithOpenCv(path, {{"projector_matrix", writeMat(k)}});
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "projector.fy must be positive"));
}

TEST_F(RigCalibrationTest, ScalarWhereAMatrixBelongsIsNamed) {
  const std::string path = pathOf("calib.yaml");
  writeWithOpenCv(path, {{"R", [](cv::FileStorage& fs, const std::string& k) { fs << k << 1.0; }}});
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "'R' is not an OpenCV matrix"));
}

TEST_F(RigCalibrationTest, MultiChannelMatrixIsRejected) {
  // 3x3 with two channels, first channel the identity: it must not be taken for a 3x3 R.
  cv::Mat two_channel(3, 3, CV_64FC2, cv::Scalar(0.0, 0.0));
  for (int i = 0; i < 3; ++i) two_channel.at<cv::Vec2d>(i, i)[0] = 1.0;
  const std::string path = pathOf("calib.yaml");
  writeWithOpenCv(path, {{"R", writeMat(two_channel)}});
  EXPECT_TRUE(failsWith([&] { io::readRigCalibration(path); }, path, "'R' must have one channel"));
}

}  // namespace
}  // namespace binpick::test
