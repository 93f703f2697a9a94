// OpenCV's PPF detector + ICP behind the benchmark's PoseMethod: on a small simulated pile it
// must find the parts within the paper's thresholds (diam/10, 10 degrees), which fails if the
// pose convention (model -> camera) or the units (metres vs relative steps) were wrong; and it
// must return nothing, without throwing, when the bin holds no measured point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "bench_test_support.hpp"
#include "binpick/evaluation/evaluation.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/pile.hpp"
#include "experiment.hpp"
#include "opencv_ppf_method.hpp"

namespace binpick::bench {
namespace {

// The model at twice binpick's step (tau_d = 0.08): OpenCV's training and matching are quadratic
// in the points per hash bucket, and the l_bracket's flat faces fill a few buckets with most
// pairs, so binpick's own resolution (tau_d = 0.04) takes ~30 s to train and minutes to match.
estimation::ModelParams coarseModel() {
  estimation::ModelParams params;
  params.sampling_ratio = 0.08f;
  return params;
}

struct Fixture {
  simulation::Part part = simulation::makePart("l_bracket");
  estimation::PreparedModel model = estimation::prepareModel(io::ModelGeometry{part.mesh, {}}, coarseModel());
  simulation::PileParams pile;
  simulation::PileScene scene;

  Fixture() {
    // A bin small enough for the parts to lean on each other (as in tests/estimation): parts
    // lying flat show one planar face, whose point pairs all share one feature and which OpenCV
    // matches upside down as readily as upright.
    pile.objects = 8;
    pile.seed = 1;
    pile.depth_noise = 0.0;
    pile.bin_length = 0.24;
    pile.bin_width = 0.18;
    scene = simulation::generatePile(part.mesh, pile);
  }
};

const Fixture& fixture() {
  static const Fixture f;  // the pile takes a moment; both tests share it
  return f;
}

MethodSetup setupFor(const Fixture& f) {
  MethodSetup setup;
  setup.model = &f.model;
  setup.max_objects = f.pile.objects;
  return setup;
}

evaluation::Score score(const Fixture& f, const std::vector<Eigen::Isometry3f>& poses) {
  return scorePoses(poses, f.scene.objects, f.part, f.model.diameter);
}

TEST(OpenCvPpfMethod, FindsThePartsOfASmallPile) {
  const Fixture& f = fixture();
  const OpenCvPpfMethod method(setupFor(f));
  EXPECT_EQ(method.name(), "opencv_ppf");

  const MethodInput input{&f.scene.cloud, evaluation::binInterior(f.scene, f.pile)};
  const std::vector<Eigen::Isometry3f> poses = method.detect(input);
  ASSERT_LE(poses.size(), static_cast<std::size_t>(f.pile.objects));

  const evaluation::Score s = score(f, poses);
  const std::string what = describeScore(s, poses.size());
  ASSERT_GE(s.findable, 2) << what;  // the pile itself: enough visible parts to test anything
  // Measured: 2 of 5 findable, the first two detections correct (OpenCV's PPF is weak on this
  // planar part: 6 of 20 on the 20-part pile at binpick's resolution). Wrong conventions or units
  // find nothing at all.
  EXPECT_GE(s.found, 2) << what;
  ASSERT_FALSE(s.matched_object.empty()) << what;
  EXPECT_GE(s.matched_object.front(), 0) << "the best detection is wrong; " << what;
}

// One part seen from an oblique view: the scene is the camera-facing half of binpick's sampling
// of the part's surface (at half the method's step), placed by a known T_camera_model. The best
// pose must be that T, not its inverse (camera -> model) nor off by a unit factor.
TEST(OpenCvPpfMethod, ReturnsModelToCameraPosesInMetres) {
  const Fixture& f = fixture();
  estimation::ModelParams dense_params;
  dense_params.sampling_ratio = 0.04f;
  const estimation::PreparedModel dense = estimation::prepareModel(io::ModelGeometry{f.part.mesh, {}}, dense_params);

  Eigen::Isometry3f T_camera_model = Eigen::Isometry3f::Identity();
  const Eigen::Vector3f axis = Eigen::Vector3f(1.0f, -2.0f, 0.5f).normalized();
  T_camera_model.linear() = Eigen::AngleAxisf(2.0f, axis).toRotationMatrix();
  T_camera_model.translation() = Eigen::Vector3f(0.03f, -0.02f, 0.8f);
  io::PointCloud cloud;
  for (std::size_t i = 0; i < dense.size(); ++i) {
    const Eigen::Vector3f p = T_camera_model * dense.points[i];
    if ((T_camera_model.linear() * dense.normals[i]).dot(p) < 0.0f) cloud.points.push_back(p);
  }
  estimation::CropBox crop;
  crop.T_camera_box.translation() = T_camera_model.translation();
  crop.half_extents = Eigen::Vector3f::Constant(0.2f);

  const OpenCvPpfMethod method(setupFor(f));
  const std::vector<Eigen::Isometry3f> poses = method.detect(MethodInput{&cloud, crop});
  ASSERT_FALSE(poses.empty());
  const Eigen::Isometry3f& best = poses.front();
  EXPECT_LT((best.translation() - T_camera_model.translation()).norm(), f.model.diameter / 10.0f)
      << "got t = " << best.translation().transpose();
  double angle_deg = 180.0;  // to the nearest of the part's symmetric poses
  for (const Eigen::Matrix3d& s : f.part.symmetry.discrete) {
    const Eigen::Matrix3d truth = T_camera_model.linear().cast<double>() * s;
    const Eigen::AngleAxisd error(truth.transpose() * best.linear().cast<double>());
    angle_deg = std::min(angle_deg, error.angle() * 180.0 / M_PI);
  }
  // Measured 11 degrees: OpenCV turns its winning alpha bin (24 degrees wide, see the params)
  // into the bin's lower edge, and its ICP does not always take the rest out. An inverted pose
  // or a unit error is off by metres or arbitrary rotations, far beyond this bound.
  EXPECT_LT(angle_deg, 25.0);
}

TEST(OpenCvPpfMethod, NaNOnlyAndEmptyCloudsGiveNoPoses) {
  const Fixture& f = fixture();
  const OpenCvPpfMethod method(setupFor(f));
  const estimation::CropBox crop = evaluation::binInterior(f.scene, f.pile);

  testing::expectNoPosesWithoutPoints(method, crop);
  std::vector<Eigen::Isometry3f> poses;

  // A few points, all in one plane inside the bin: too few and too flat for OpenCV's quantisation.
  io::PointCloud few;
  const Eigen::Vector3f centre = crop.T_camera_box.translation();
  for (int i = 0; i < 5; ++i) {
    few.points.push_back(centre + Eigen::Vector3f(0.001f * i, 0.0f, 0.0f));
  }
  EXPECT_NO_THROW(poses = method.detect(MethodInput{&few, crop}));
  EXPECT_TRUE(poses.empty());
}

}  // namespace
}  // namespace binpick::bench
