// Calibrations written by other tools (cv::FileStorage XML / YAML / JSON) read into a RigCalibration:
// the real file of kamino410's procam-calibration, other tools' key names and misspellings, keys
// given by role, rotation vectors, board poses composed, units, and the errors that name what is
// missing or wrong.
#include "binpick/io/opencv_calibration.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <functional>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/eigen.hpp>
#include <random>
#include <string>
#include <tuple>

#include "binpick/core/error.hpp"
#include "binpick/io/rig_calibration.hpp"
#include "io_test_support.hpp"
#include "thrown_message.hpp"

namespace binpick::test {
namespace {

using OpenCvCalibrationTest = IoTest;

// The calibration of the real rig in the shared data set: written by kamino410/procam-calibration
// (cv::stereoCalibrate, translation in millimetres, the rotation under the misspelt key
// `roration`, the camera's size as numpy's (rows, cols) under `img_shape`, no projector size).
const std::string kKaminoCalibration = BINPICK_KAMINO_CALIBRATION;

// The projector's size is not in kamino410's file (its tool takes it on the command line) and the
// values read do not depend on it: 1920 x 1080 stands in for it.
io::OpenCvCalibrationOptions kaminoOptions() {
  io::OpenCvCalibrationOptions options;
  options.projector_width = 1920;
  options.projector_height = 1080;
  return options;
}

#define SKIP_WITHOUT_KAMINO_FILE()                                                                              \
  if (!std::filesystem::exists(kKaminoCalibration)) {                                                           \
    GTEST_SKIP() << "the real data set is missing (" << kKaminoCalibration                                      \
                 << "): it is beside the project's clone in CI; get kamino410-procam-calibration there to run " \
                    "this test";                                                                                \
  }

Eigen::Matrix3d openCvMatrix(const cv::FileStorage& fs, const std::string& key) {
  cv::Mat m;
  fs[key] >> m;
  Eigen::Matrix3d e;
  cv::cv2eigen(m, e);
  return e;
}

std::vector<double> openCvValues(const cv::FileStorage& fs, const std::string& key) {
  cv::Mat m;
  fs[key] >> m;
  m = m.reshape(1, 1);
  return std::vector<double>(m.begin<double>(), m.end<double>());
}

void expectLensFromMatrix(const io::LensIntrinsics& lens, const Eigen::Matrix3d& k, const std::vector<double>& d) {
  EXPECT_DOUBLE_EQ(lens.fx, k(0, 0));
  EXPECT_DOUBLE_EQ(lens.fy, k(1, 1));
  EXPECT_DOUBLE_EQ(lens.cx, k(0, 2));
  EXPECT_DOUBLE_EQ(lens.cy, k(1, 2));
  ASSERT_EQ(d.size(), 5u);
  for (int i = 0; i < 5; ++i) EXPECT_DOUBLE_EQ(lens.distortion[i], d[i]) << "coefficient " << i;
}

TEST_F(OpenCvCalibrationTest, KaminoFileReadsWithItsIntrinsicsAndTheTranslationInMetres) {
  SKIP_WITHOUT_KAMINO_FILE();
  const io::RigCalibration rig = io::readOpenCvCalibration(kKaminoCalibration, kaminoOptions());
  const cv::FileStorage xml(kKaminoCalibration, cv::FileStorage::READ);
  // img_shape is [1024, 1280]: rows first.
  EXPECT_EQ(rig.camera.width, 1280);
  EXPECT_EQ(rig.camera.height, 1024);
  EXPECT_EQ(rig.projector.width, 1920);
  EXPECT_EQ(rig.projector.height, 1080);
  expectLensFromMatrix(rig.camera, openCvMatrix(xml, "cam_int"), openCvValues(xml, "cam_dist"));
  expectLensFromMatrix(rig.projector, openCvMatrix(xml, "proj_int"), openCvValues(xml, "proj_dist"));
  const Eigen::Matrix3d r = openCvMatrix(xml, "roration");
  EXPECT_LT((rig.T_projector_camera.linear() - r).cwiseAbs().maxCoeff(), 1e-9);
  const std::vector<double> t = openCvValues(xml, "translation");
  for (int i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(rig.T_projector_camera.translation()[i], t[i] / 1000.0);
  // The README's figure: a baseline of about 644 mm, mostly vertical.
  EXPECT_NEAR(rig.T_projector_camera.translation().norm(), 0.644, 0.001);
  EXPECT_NO_THROW(rig.validate());
}

TEST_F(OpenCvCalibrationTest, KaminoFileInMetresIsRefusedAsImplausible) {
  SKIP_WITHOUT_KAMINO_FILE();
  io::OpenCvCalibrationOptions options = kaminoOptions();
  options.units = io::LengthUnit::Metres;
  const std::string message = thrownMessage([&] { io::readOpenCvCalibration(kKaminoCalibration, options); });
  EXPECT_NE(message.find(": the baseline is 644."), std::string::npos) << message;
  EXPECT_NE(message.find(" m read as metres: is the file in millimetres (--units mm)?"), std::string::npos) << message;
}

TEST_F(OpenCvCalibrationTest, KaminoFileWithoutProjectorSizeNamesTheOption) {
  SKIP_WITHOUT_KAMINO_FILE();
  EXPECT_EQ(thrownMessage([&] { io::readOpenCvCalibration(kKaminoCalibration, {}); }),
            kKaminoCalibration +
                ": no projector image size (tried projector_width/projector_height, proj_width/proj_height, "
                "projector_size, proj_size, projectorSize, projector_resolution, proj_shape, projector_shape; give "
                "--projector WxH)");
}

TEST_F(OpenCvCalibrationTest, KaminoFileRoundTripsThroughCalibYaml) {
  SKIP_WITHOUT_KAMINO_FILE();
  const io::RigCalibration rig = io::readOpenCvCalibration(kKaminoCalibration, kaminoOptions());
  const std::string path = pathOf("calib.yaml");
  io::writeRigCalibration(path, rig);
  const io::RigCalibration back = io::readRigCalibration(path);
  EXPECT_EQ(back.camera.width, 1280);
  EXPECT_EQ(back.projector.height, 1080);
  EXPECT_DOUBLE_EQ(back.camera.fx, rig.camera.fx);
  EXPECT_DOUBLE_EQ(back.projector.cy, rig.projector.cy);
  for (int i = 0; i < 5; ++i) EXPECT_DOUBLE_EQ(back.projector.distortion[i], rig.projector.distortion[i]);
  EXPECT_LT((back.T_projector_camera.matrix() - rig.T_projector_camera.matrix()).cwiseAbs().maxCoeff(), 1e-15);
}

// --- files of other tools, written here ---------------------------------------------------------

io::RigCalibration sampleRig() {
  io::RigCalibration rig;
  rig.camera.width = 2448;
  rig.camera.height = 2048;
  rig.camera.fx = 2401.5;
  rig.camera.fy = 2400.25;
  rig.camera.cx = 1222.75;
  rig.camera.cy = 1030.5;
  rig.camera.distortion = {-0.091, 0.134, 2.5e-4, -1.5e-4, -0.021};
  rig.projector.width = 1920;
  rig.projector.height = 1080;
  rig.projector.fx = 2210.0;
  rig.projector.fy = 2208.5;
  rig.projector.cx = 955.5;
  rig.projector.cy = 1075.0;
  rig.projector.distortion = {0.012, -0.031, 0.0, 0.0, 0.0};
  rig.T_projector_camera.linear() =
      Eigen::AngleAxisd(0.21, Eigen::Vector3d(0.1, 0.97, -0.05).normalized()).toRotationMatrix();
  rig.T_projector_camera.translation() = Eigen::Vector3d(-0.2315, 0.0123, 0.0457);
  return rig;
}

cv::Mat cameraMatrix(const io::LensIntrinsics& lens) {
  return (cv::Mat_<double>(3, 3) << lens.fx, 0, lens.cx, 0, lens.fy, lens.cy, 0, 0, 1);
}

cv::Mat distortionRow(const io::LensIntrinsics& lens) {
  return cv::Mat(1, 5, CV_64F, const_cast<double*>(lens.distortion.data())).clone();
}

cv::Mat rotationMatrix(const io::RigCalibration& rig) {
  cv::Mat r;
  cv::eigen2cv(Eigen::Matrix3d(rig.T_projector_camera.linear()), r);
  return r;
}

cv::Mat translationColumn(const Eigen::Vector3d& t, double scale) {
  return (cv::Mat_<double>(3, 1) << t.x() * scale, t.y() * scale, t.z() * scale);
}

using Writer = std::function<void(cv::FileStorage&)>;

std::string writeStorage(const std::string& path, const Writer& write) {
  cv::FileStorage fs(path, cv::FileStorage::WRITE);
  write(fs);
  return path;
}

void expectSameRig(const io::RigCalibration& a, const io::RigCalibration& b, double pose_tolerance = 1e-12) {
  for (const auto& [x, y] : {std::pair{&a.camera, &b.camera}, std::pair{&a.projector, &b.projector}}) {
    EXPECT_EQ(x->width, y->width);
    EXPECT_EQ(x->height, y->height);
    EXPECT_DOUBLE_EQ(x->fx, y->fx);
    EXPECT_DOUBLE_EQ(x->fy, y->fy);
    EXPECT_DOUBLE_EQ(x->cx, y->cx);
    EXPECT_DOUBLE_EQ(x->cy, y->cy);
    for (int i = 0; i < 5; ++i) EXPECT_DOUBLE_EQ(x->distortion[i], y->distortion[i]);
  }
  EXPECT_LT((a.T_projector_camera.matrix() - b.T_projector_camera.matrix()).cwiseAbs().maxCoeff(), pose_tolerance);
}

// OpenCV's stereo_calib sample: M1 D1 M2 D2 R T, here with the sizes as cv::Size (width first)
// and the translation in metres.
Writer stereoCalibSample(const io::RigCalibration& rig) {
  return [rig](cv::FileStorage& fs) {
    fs << "imageSize" << cv::Size(rig.camera.width, rig.camera.height);
    fs << "projector_size" << cv::Size(rig.projector.width, rig.projector.height);
    fs << "M1" << cameraMatrix(rig.camera) << "D1" << distortionRow(rig.camera);
    fs << "M2" << cameraMatrix(rig.projector) << "D2" << distortionRow(rig.projector);
    fs << "R" << rotationMatrix(rig) << "T" << translationColumn(rig.T_projector_camera.translation(), 1.0);
  };
}

TEST_F(OpenCvCalibrationTest, StereoCalibNamesInYamlAndMetres) {
  const io::RigCalibration rig = sampleRig();
  const std::string path = writeStorage(pathOf("stereo.yml"), stereoCalibSample(rig));
  io::OpenCvCalibrationOptions options;
  options.units = io::LengthUnit::Metres;
  expectSameRig(io::readOpenCvCalibration(path, options), rig);
}

TEST_F(OpenCvCalibrationTest, JsonFilesReadToo) {
  const io::RigCalibration rig = sampleRig();
  const std::string path = writeStorage(pathOf("stereo.json"), stereoCalibSample(rig));
  io::OpenCvCalibrationOptions options;
  options.units = io::LengthUnit::Metres;
  expectSameRig(io::readOpenCvCalibration(path, options), rig);
}

// Moreno & Taubin's scan3d-capture names (cam_K, cam_kc), two misspellings of R and T (`rot`,
// `trans`), numpy's shapes (rows first) and a hand-typed file: plain lists, no OpenCV header.
TEST_F(OpenCvCalibrationTest, HandTypedYamlWithOtherNamesAndPlainLists) {
  const std::string path = writeFile("typed.yaml",
                                     "%YAML:1.0\n"
                                     "img_shape: [ 2048, 2448 ]\n"
                                     "proj_shape: [ 1080, 1920, 3 ]\n"
                                     "cam_K: [ [ 2401.5, 0, 1222.75 ], [ 0, 2400.25, 1030.5 ], [ 0, 0, 1 ] ]\n"
                                     "cam_kc: [ -0.091, 0.134, 2.5e-4, -1.5e-4, -0.021 ]\n"
                                     "proj_K: [ 2210.0, 0, 955.5, 0, 2208.5, 1075.0, 0, 0, 1 ]\n"
                                     "proj_kc: [ 0.012, -0.031, 0, 0 ]\n"
                                     "rot: [ 0, 0, 0 ]\n"
                                     "trans: [ -231.5, 12.3, 45.7 ]\n");
  const io::RigCalibration rig = io::readOpenCvCalibration(path, {});
  io::RigCalibration expected = sampleRig();
  expected.T_projector_camera.linear().setIdentity();
  expectSameRig(rig, expected, 1e-15);
}

TEST_F(OpenCvCalibrationTest, KeysGivenByRoleOverrideTheNamesTried) {
  const io::RigCalibration rig = sampleRig();
  const std::string path = writeStorage(pathOf("own.yml"), [&](cv::FileStorage& fs) {
    fs << "sensor_w" << rig.camera.width << "sensor_h" << rig.camera.height;
    fs << "intrinsics_a" << cameraMatrix(rig.camera) << "lens_a" << distortionRow(rig.camera);
    fs << "intrinsics_b" << cameraMatrix(rig.projector) << "lens_b" << distortionRow(rig.projector);
    fs << "Rab" << rotationMatrix(rig) << "tab" << translationColumn(rig.T_projector_camera.translation(), 1000.0);
    // A key of the names tried, for something else: the role's key given by name wins.
    fs << "R" << cv::Mat::eye(3, 3, CV_64F);
  });
  io::OpenCvCalibrationOptions options;
  options.camera_width = rig.camera.width;
  options.camera_height = rig.camera.height;
  options.projector_width = rig.projector.width;
  options.projector_height = rig.projector.height;
  options.keys = {{"camera_matrix", "intrinsics_a"},
                  {"camera_distortion", "lens_a"},
                  {"projector_matrix", "intrinsics_b"},
                  {"projector_distortion", "lens_b"},
                  {"rotation", "Rab"},
                  {"translation", "tab"}};
  expectSameRig(io::readOpenCvCalibration(path, options), rig, 1e-15);
  options.keys["rotation"] = "Rba";
  EXPECT_EQ(thrownMessage([&] { io::readOpenCvCalibration(path, options); }),
            path + ": no key 'Rba' for the rotation from camera to projector (given by --key rotation=Rba)");
}

TEST_F(OpenCvCalibrationTest, RotationVectorGivesTheSameRigAsTheMatrix) {
  const io::RigCalibration rig = sampleRig();
  cv::Mat rvec;
  cv::Rodrigues(rotationMatrix(rig), rvec);
  const std::string path = writeStorage(pathOf("rvec.xml"), [&](cv::FileStorage& fs) {
    stereoCalibSample(rig)(fs);
    fs << "rotation" << rvec;
  });
  io::OpenCvCalibrationOptions options;
  options.units = io::LengthUnit::Metres;
  options.keys["rotation"] = "rotation";  // R is there too: the vector is what this test reads
  expectSameRig(io::readOpenCvCalibration(path, options), rig, 1e-12);
}

TEST_F(OpenCvCalibrationTest, AMissingRoleIsNamedWithTheKeysTried) {
  const io::RigCalibration rig = sampleRig();
  const std::string path = writeStorage(pathOf("no_projector.xml"), [&](cv::FileStorage& fs) {
    fs << "img_shape" << (cv::Mat_<double>(2, 1) << rig.camera.height, rig.camera.width);
    fs << "cam_int" << cameraMatrix(rig.camera) << "cam_dist" << distortionRow(rig.camera);
    fs << "proj_dist" << distortionRow(rig.projector);
    fs << "roration" << rotationMatrix(rig) << "translation"
       << translationColumn(rig.T_projector_camera.translation(), 1000.0);
  });
  io::OpenCvCalibrationOptions options;
  options.projector_width = 1920;
  options.projector_height = 1080;
  EXPECT_EQ(thrownMessage([&] { io::readOpenCvCalibration(path, options); }),
            path +
                ": no projector matrix (tried proj_int, projector_matrix, K2, M2, proj_K, projector_intrinsic, "
                "projector_intrinsics, proj_matrix, proj_mtx; give --key projector_matrix=NAME)");
}

TEST_F(OpenCvCalibrationTest, AMissingDistortionMayBeGivenAsNone) {
  const io::RigCalibration rig = sampleRig();
  const std::string path = writeStorage(pathOf("no_projector_distortion.yml"), [&](cv::FileStorage& fs) {
    fs << "image_width" << rig.camera.width << "image_height" << rig.camera.height;
    fs << "camera_matrix" << cameraMatrix(rig.camera) << "distortion_coefficients" << distortionRow(rig.camera);
    fs << "projector_matrix" << cameraMatrix(rig.projector);
    fs << "R" << rotationMatrix(rig) << "T" << translationColumn(rig.T_projector_camera.translation(), 1000.0);
  });
  io::OpenCvCalibrationOptions options;
  options.projector_width = 1920;
  options.projector_height = 1080;
  EXPECT_TRUE(throwsNaming([&] { io::readOpenCvCalibration(path, options); },
                           "no projector distortion (tried proj_dist, D2, projector_distortion, proj_kc, "
                           "proj_distortion, projector_dist; give --key projector_distortion=NAME, or =none for a "
                           "lens without distortion)"));
  options.keys["projector_distortion"] = "none";
  const io::RigCalibration read = io::readOpenCvCalibration(path, options);
  EXPECT_FALSE(read.projector.hasDistortion());
  EXPECT_DOUBLE_EQ(read.camera.distortion[4], rig.camera.distortion[4]);
}

TEST_F(OpenCvCalibrationTest, TwoKeysForOneRoleAreRefused) {
  const io::RigCalibration rig = sampleRig();
  const std::string path = writeStorage(pathOf("both.yml"), [&](cv::FileStorage& fs) {
    stereoCalibSample(rig)(fs);
    fs << "rotation" << cv::Mat::eye(3, 3, CV_64F);
  });
  io::OpenCvCalibrationOptions options;
  options.units = io::LengthUnit::Metres;
  EXPECT_TRUE(throwsNaming([&] { io::readOpenCvCalibration(path, options); },
                           ": both 'R' and 'rotation' could be the rotation from camera to projector; give --key "
                           "rotation=NAME"));
}

// OpenCV's rational (8), thin-prism (12) and tilted (14) models: the extra terms must be zero.
TEST_F(OpenCvCalibrationTest, LongerDistortionModelsNeedTheirExtraTermsZero) {
  const io::RigCalibration rig = sampleRig();
  cv::Mat d14 = cv::Mat::zeros(1, 14, CV_64F);
  for (int i = 0; i < 5; ++i) d14.at<double>(i) = rig.camera.distortion[i];
  const auto fileWith = [&](const cv::Mat& camera_distortion) {
    return writeStorage(pathOf("rational.yml"), [&](cv::FileStorage& fs) {
      stereoCalibSample(rig)(fs);
      fs << "camera_distortion" << camera_distortion;
    });
  };
  io::OpenCvCalibrationOptions options;
  options.units = io::LengthUnit::Metres;
  options.keys["camera_distortion"] = "camera_distortion";
  for (int count : {8, 12, 14}) {
    const std::string path = fileWith(d14.colRange(0, count).t());  // as a column this time
    EXPECT_DOUBLE_EQ(io::readOpenCvCalibration(path, options).camera.distortion[4], rig.camera.distortion[4]);
  }
  d14.at<double>(5) = 0.25;   // k4
  d14.at<double>(12) = 1e-3;  // tauX
  const std::string path = fileWith(d14);
  EXPECT_TRUE(throwsNaming([&] { io::readOpenCvCalibration(path, options); },
                           "the camera distortion 'camera_distortion' has k4 = 0.250000, tauX = 0.001000: the lens "
                           "model has k1 k2 p1 p2 k3 only"));
  EXPECT_TRUE(throwsNaming([&] { io::readOpenCvCalibration(fileWith(d14.colRange(0, 6).clone()), options); },
                           "must hold 4, 5, 8, 12 or 14 coefficients (got 1x6)"));
}

TEST_F(OpenCvCalibrationTest, SizesMustAgree) {
  const io::RigCalibration rig = sampleRig();
  const std::string path = writeStorage(pathOf("sizes.yml"), [&](cv::FileStorage& fs) {
    stereoCalibSample(rig)(fs);
    fs << "img_shape" << cv::Size(rig.camera.width, rig.camera.height);  // written the wrong way round
  });
  io::OpenCvCalibrationOptions options;
  options.units = io::LengthUnit::Metres;
  EXPECT_TRUE(throwsNaming([&] { io::readOpenCvCalibration(path, options); },
                           "the camera image size is 2448x2048 by 'imageSize' but 2048x2448 by 'img_shape'"));
  const std::string good = writeStorage(pathOf("good.yml"), stereoCalibSample(rig));
  options.camera_width = 1224;
  options.camera_height = 1024;
  EXPECT_TRUE(throwsNaming([&] { io::readOpenCvCalibration(good, options); },
                           "the camera image is 2448x2048 by 'imageSize' but 1224x1024 by --camera"));
}

TEST_F(OpenCvCalibrationTest, BadValuesAreNamed) {
  const io::RigCalibration rig = sampleRig();
  io::OpenCvCalibrationOptions options;
  options.units = io::LengthUnit::Metres;
  const auto fileWith = [&](const std::string& key, const cv::Mat& value) {
    return writeStorage(pathOf("bad.yml"), [&](cv::FileStorage& fs) {
      stereoCalibSample(rig)(fs);
      fs << key << value;
    });
  };
  options.keys["rotation"] = "bad_R";
  EXPECT_TRUE(throwsNaming([&] { io::readOpenCvCalibration(fileWith("bad_R", 1.01 * rotationMatrix(rig)), options); },
                           "the rotation from camera to projector 'bad_R' is not a rotation"));
  EXPECT_TRUE(throwsNaming([&] { io::readOpenCvCalibration(fileWith("bad_R", cv::Mat::eye(2, 2, CV_64F)), options); },
                           "'bad_R' must be a 3x3 rotation matrix or a 3-value rotation vector (got 2x2)"));
  // Printed to 6 digits a rotation is no longer orthonormal to 1e-6: it is made so.
  cv::Mat rounded = rotationMatrix(rig);
  for (auto it = rounded.begin<double>(); it != rounded.end<double>(); ++it) *it = std::round(*it * 1e6) / 1e6;
  EXPECT_NO_THROW(io::readOpenCvCalibration(fileWith("bad_R", rounded), options));
  options.keys.erase("rotation");
  options.keys["camera_matrix"] = "K_skew";
  cv::Mat skewed = cameraMatrix(rig.camera);
  skewed.at<double>(0, 1) = 0.5;
  EXPECT_TRUE(throwsNaming([&] { io::readOpenCvCalibration(fileWith("K_skew", skewed), options); },
                           "the camera matrix 'K_skew' has skew"));
  EXPECT_TRUE(
      throwsNaming([&] { io::readOpenCvCalibration(fileWith("K_skew", cameraMatrix(rig.camera).t()), options); },
                   "the camera matrix 'K_skew' is transposed"));
}

TEST_F(OpenCvCalibrationTest, CorruptMatrixSizesAreRefusedBeforeAllocating) {
  const std::string path = writeFile("huge.yml",
                                     "%YAML:1.0\n"
                                     "M1: !!opencv-matrix\n"
                                     "   rows: 60000\n"
                                     "   cols: 60000\n"
                                     "   dt: d\n"
                                     "   data: [ 1., 0., 0. ]\n");
  io::OpenCvCalibrationOptions options;
  options.camera_width = options.projector_width = 1280;
  options.camera_height = options.projector_height = 1024;
  EXPECT_EQ(thrownMessage([&] { io::readOpenCvCalibration(path, options); }),
            path + ": 'M1' cannot be read: it claims more than 65536 values");
}

// Each device's pose of the board in every view, as calibrateCamera returns them (rvecs, tvecs
// stacked n x 3): the projector's pose relative to the camera is their composition.
TEST_F(OpenCvCalibrationTest, BoardPosesAreComposed) {
  const io::RigCalibration rig = sampleRig();
  std::mt19937 random(5);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  constexpr int kViews = 6;
  cv::Mat cam_rvecs(kViews, 3, CV_64F), cam_tvecs(kViews, 3, CV_64F), proj_rvecs(kViews, 3, CV_64F),
      proj_tvecs(kViews, 3, CV_64F);
  for (int v = 0; v < kViews; ++v) {
    Eigen::Isometry3d camera_board = Eigen::Isometry3d::Identity();
    camera_board.linear() =
        Eigen::AngleAxisd(0.3 * uniform(random), Eigen::Vector3d(uniform(random), uniform(random), 1).normalized())
            .toRotationMatrix();
    camera_board.translation() = Eigen::Vector3d(0.1 * uniform(random), 0.1 * uniform(random), 0.8);
    const Eigen::Isometry3d projector_board = rig.T_projector_camera * camera_board;
    for (const auto& [pose, rvecs, tvecs] :
         {std::tuple{camera_board, &cam_rvecs, &cam_tvecs}, std::tuple{projector_board, &proj_rvecs, &proj_tvecs}}) {
      const Eigen::AngleAxisd angle_axis(pose.linear());
      const Eigen::Vector3d rvec = angle_axis.angle() * angle_axis.axis();
      for (int i = 0; i < 3; ++i) {
        rvecs->at<double>(v, i) = rvec[i];
        tvecs->at<double>(v, i) = 1000.0 * pose.translation()[i];  // millimetres
      }
    }
  }
  const std::string path = writeStorage(pathOf("poses.yml"), [&](cv::FileStorage& fs) {
    fs << "imageSize" << cv::Size(rig.camera.width, rig.camera.height);
    fs << "proj_size" << cv::Size(rig.projector.width, rig.projector.height);
    fs << "cam_int" << cameraMatrix(rig.camera) << "cam_dist" << distortionRow(rig.camera);
    fs << "proj_int" << cameraMatrix(rig.projector) << "proj_dist" << distortionRow(rig.projector);
    fs << "cam_rvecs" << cam_rvecs << "cam_tvecs" << cam_tvecs;
    fs << "proj_rvecs" << proj_rvecs << "proj_tvecs" << proj_tvecs;
  });
  expectSameRig(io::readOpenCvCalibration(path, {}), rig, 1e-9);
  // Views out of order do not compose into one rig.
  const std::string shuffled = writeStorage(pathOf("shuffled.yml"), [&](cv::FileStorage& fs) {
    fs << "imageSize" << cv::Size(rig.camera.width, rig.camera.height);
    fs << "proj_size" << cv::Size(rig.projector.width, rig.projector.height);
    fs << "cam_int" << cameraMatrix(rig.camera) << "cam_dist" << distortionRow(rig.camera);
    fs << "proj_int" << cameraMatrix(rig.projector) << "proj_dist" << distortionRow(rig.projector);
    cv::Mat reversed;
    cv::flip(cam_rvecs, reversed, 0);
    fs << "cam_rvecs" << reversed << "cam_tvecs" << cam_tvecs;
    fs << "proj_rvecs" << proj_rvecs << "proj_tvecs" << proj_tvecs;
  });
  EXPECT_TRUE(
      throwsNaming([&] { io::readOpenCvCalibration(shuffled, {}); }, "the board poses do not compose into one rig"));
}

// Python's cv2.FileStorage writes numpy's stacked column vectors (n, 3, 1) as n-dimensional matrices.
TEST_F(OpenCvCalibrationTest, NumpyStacksOfBoardPosesAreComposed) {
  const std::string path = writeFile("numpy.yaml",
                                     "%YAML:1.0\n"
                                     "img_shape: [ 1024, 1280 ]\n"
                                     "proj_shape: [ 800, 1280 ]\n"
                                     "cam_int: [ 1600, 0, 640, 0, 1600, 512, 0, 0, 1 ]\n"
                                     "cam_dist: [ 0, 0, 0, 0, 0 ]\n"
                                     "proj_int: [ 1400, 0, 640, 0, 1400, 790, 0, 0, 1 ]\n"
                                     "proj_dist: [ 0, 0, 0, 0 ]\n"
                                     "cam_rvecs: !!opencv-nd-matrix\n"
                                     "   sizes: [ 2, 3, 1 ]\n"
                                     "   dt: d\n"
                                     "   data: [ 0., 0., 0., 0., 0., 0. ]\n"
                                     "cam_tvecs: !!opencv-nd-matrix\n"
                                     "   sizes: [ 2, 3, 1 ]\n"
                                     "   dt: d\n"
                                     "   data: [ 0., 0., 1000., 100., 0., 1000. ]\n"
                                     "proj_rvecs: !!opencv-nd-matrix\n"
                                     "   sizes: [ 2, 3, 1 ]\n"
                                     "   dt: d\n"
                                     "   data: [ 0., 0., 0., 0., 0., 0. ]\n"
                                     "proj_tvecs: !!opencv-nd-matrix\n"
                                     "   sizes: [ 2, 3, 1 ]\n"
                                     "   dt: d\n"
                                     "   data: [ -250., 10., 1040., -150., 10., 1040. ]\n");
  const io::RigCalibration rig = io::readOpenCvCalibration(path, {});
  EXPECT_EQ(rig.projector.width, 1280);
  EXPECT_EQ(rig.projector.height, 800);
  EXPECT_LT((rig.T_projector_camera.linear() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((rig.T_projector_camera.translation() - Eigen::Vector3d(-0.25, 0.01, 0.04)).norm(), 1e-15);
}

TEST_F(OpenCvCalibrationTest, OptionsAreChecked) {
  EXPECT_EQ(io::lengthUnitFromName("mm"), io::LengthUnit::Millimetres);
  EXPECT_EQ(io::lengthUnitFromName("m"), io::LengthUnit::Metres);
  EXPECT_EQ(thrownMessage([] { io::lengthUnitFromName("cm"); }), "unknown length unit 'cm' (mm or m)");
  io::OpenCvCalibrationOptions options;
  options.keys["rotaton"] = "R";
  EXPECT_TRUE(throwsNaming([&] { options.validate(); }, "unknown calibration role 'rotaton' (roles: camera_matrix,"));
  options.keys.clear();
  options.projector_width = 1920;
  EXPECT_TRUE(throwsNaming([&] { options.validate(); }, "projector_width/projector_height must be both 0 or both"));
}

}  // namespace
}  // namespace binpick::test
