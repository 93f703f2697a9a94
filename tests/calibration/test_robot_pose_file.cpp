// poses.txt and the views directory: every convention reads back, every mistake names its line
// and view.
#include "binpick/calibration/robot_pose_file.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "binpick/calibration/hand_eye_views.hpp"
#include "binpick/io/image_file.hpp"
#include "temp_directory_test.hpp"
#include "thrown_message.hpp"

namespace binpick::calibration {
namespace {

using test::throwsNaming;
constexpr double kDegree = 3.14159265358979323846 / 180.0;

RobotPoseFile parse(const std::string& text) { return parseRobotPoses(text, "poses.txt"); }

TEST(RobotPoseFile, ReadsMillimetresAndTheNamedConvention) {
  const RobotPoseFile file = parse(
      "# taught on the pendant\n\norientation: euler_zyx\n"
      "view_a 600 -25.5 300 90 0 180\n"
      "  # a comment between views\n"
      "view.b-2 0 0 1000 0 0 0\n");
  EXPECT_EQ(file.orientation, core::Orientation::EulerZYX);
  ASSERT_EQ(file.poses.size(), 2u);
  EXPECT_EQ(file.poses[0].view, "view_a");
  EXPECT_EQ(file.poses[0].line, 4);
  EXPECT_TRUE(file.poses[0].T_base_flange.translation().isApprox(Eigen::Vector3d(0.6, -0.0255, 0.3)));
  // KUKA A, B, C = 90, 0, 180: Rz(90) Rx(180).
  const Eigen::Matrix3d expected = (Eigen::AngleAxisd(90 * kDegree, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(180 * kDegree, Eigen::Vector3d::UnitX()))
                                       .matrix();
  EXPECT_LT((file.poses[0].T_base_flange.linear() - expected).norm(), 1e-12);
  EXPECT_NEAR(file.poses[1].T_base_flange.translation().z(), 1.0, 1e-12);
}

TEST(RobotPoseFile, EveryConventionRoundTrips) {
  for (const char* name : {"quaternion", "euler_zyx", "fixed_xyz", "rotation_vector", "euler_xyz"}) {
    RobotPoseFile file;
    file.orientation = core::orientationFromName(name);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()).matrix();
    pose.translation() = Eigen::Vector3d(0.61234567, -0.2, 0.45);
    file.poses.push_back({"v1", pose, 0});
    const RobotPoseFile back = parse(formatRobotPoses(file));
    SCOPED_TRACE(name);
    ASSERT_EQ(back.poses.size(), 1u);
    EXPECT_LT((back.poses[0].T_base_flange.translation() - pose.translation()).norm(), 1e-7);
    EXPECT_LT((back.poses[0].T_base_flange.linear() - pose.linear()).norm(), 1e-8);
  }
}

TEST(RobotPoseFile, MistakesNameTheLineAndView) {
  EXPECT_TRUE(
      throwsNaming([] { parse("view_1 1 2 3 0 0 0\n"); }, "poses.txt:1: the first line must be 'orientation: NAME'"));
  EXPECT_TRUE(throwsNaming([] { parse("orientation: euler_zxz\n"); }, "poses.txt:1: "));
  EXPECT_TRUE(throwsNaming([] { parse("orientation: euler_zxz\n"); }, "euler_zyx"));  // the names
  EXPECT_TRUE(throwsNaming([] { parse("# only comments\n"); }, "no 'orientation: NAME' line"));
  EXPECT_TRUE(throwsNaming([] { parse("orientation: quaternion\nv1 1 2 3 1 0 0\n"); },
                           "poses.txt:2: view v1: expected x y z (mm) and 4 quaternion values, got 6"));
  EXPECT_TRUE(throwsNaming([] { parse("orientation: fixed_xyz\nv1 1 2 3 0 0 0 0\n"); },
                           "poses.txt:2: view v1: expected x y z (mm) and 3 fixed_xyz values, got 7"));
  EXPECT_TRUE(throwsNaming([] { parse("orientation: fixed_xyz\n\nv1 1 nan 3 0 0 0\n"); },
                           "poses.txt:3: view v1: 'nan' is not a finite number"));
  EXPECT_TRUE(throwsNaming([] { parse("orientation: fixed_xyz\nv1 1 2 3 0 0 1e999\n"); },
                           "view v1: '1e999' is not a finite number"));
  EXPECT_TRUE(throwsNaming([] { parse("orientation: fixed_xyz\nv1 1 2 3 0 0 9x\n"); }, "'9x'"));
  EXPECT_TRUE(throwsNaming([] { parse("orientation: quaternion\nv1 1 2 3 0 0 0 0\n"); },
                           "poses.txt:2: view v1: "));  // a zero quaternion
  EXPECT_TRUE(throwsNaming([] { parse("orientation: euler_xyz\nv1 1 2 3 0 0 0\nv2 1 2 3 0 0 0\nv1 0 0 0 0 0 0\n"); },
                           "poses.txt:4: view v1 is listed twice (first on line 2)"));
  EXPECT_TRUE(throwsNaming([] { parse("orientation: euler_xyz\nview/1 1 2 3 0 0 0\n"); },
                           "poses.txt:2: 'view/1' is not a view name"));
}

// Values the conversion would normalise or wrap silently are more likely another convention.
TEST(RobotPoseFile, RotationsOfAnotherConventionAreRefused) {
  EXPECT_TRUE(throwsNaming([] { parse("orientation: quaternion\nv1 1 2 3 0.5 1.2 0 0\n"); },
                           "poses.txt:2: view v1: quaternion has norm 1.3; not a rotation"));
  EXPECT_NO_THROW(parse("orientation: quaternion\nv1 1 2 3 1.005 0 0 0\n"));  // rounding: normalised
  EXPECT_TRUE(throwsNaming([] { parse("orientation: rotation_vector\nv1 1 2 3 0 3.3 0\n"); },
                           "poses.txt:2: view v1: rotation vector of length 3.3 rad is longer than pi"));
  EXPECT_NO_THROW(parse("orientation: rotation_vector\nv1 1 2 3 0 3.14159265 0\n"));
}

class HandEyeViewsDirectory : public test::TempDirectoryTest {
 protected:
  void write(const std::string& name, const std::string& text) { std::ofstream(pathOf(name)) << text; }
  void image(const std::string& view) {
    io::writeImageFile(pathOf(view + ".png"), cv::Mat(8, 8, CV_8UC1, cv::Scalar(128)));
  }
};

TEST_F(HandEyeViewsDirectory, PairsEveryPoseWithItsImage) {
  write("poses.txt", "orientation: rotation_vector\nb 1 2 3 0 0 0\na 4 5 6 0 0 0.5\n");
  image("a");
  image("b");
  write("notes.txt", "not a view");
  const std::vector<HandEyeViewFile> views = listHandEyeViews(root());
  ASSERT_EQ(views.size(), 2u);
  EXPECT_EQ(views[0].name, "b");  // the file's order
  EXPECT_EQ(views[1].image_path, pathOf("a.png"));
}

TEST_F(HandEyeViewsDirectory, APoseWithoutImageIsNamed) {
  write("poses.txt", "orientation: euler_zyx\nv1 1 2 3 0 0 0\nv2 1 2 3 0 0 0\n");
  image("v1");
  EXPECT_TRUE(throwsNaming([&] { listHandEyeViews(root()); }, "poses.txt:3: view v2 has a robot pose but no image"));
}

TEST_F(HandEyeViewsDirectory, AnImageWithoutPoseIsNamed) {
  write("poses.txt", "orientation: euler_zyx\nv1 1 2 3 0 0 0\n");
  image("v1");
  image("v9");
  EXPECT_TRUE(throwsNaming([&] { listHandEyeViews(root()); }, "view v9 has an image but no robot pose"));
  EXPECT_TRUE(throwsNaming([&] { listHandEyeViews(root()); }, "(1 image(s) without a pose, 1 pose(s))"));
}

TEST_F(HandEyeViewsDirectory, AMissingPoseFileIsNamed) {
  image("v1");
  EXPECT_TRUE(throwsNaming([&] { listHandEyeViews(root()); }, "poses.txt: missing"));
  EXPECT_TRUE(throwsNaming([&] { listHandEyeViews(pathOf("nowhere")); }, "not a directory"));
}

}  // namespace
}  // namespace binpick::calibration
