#include "pcl_ppf_method.hpp"

// What PCL 1.13's PPFRegistration does (registration/impl/ppf_registration.hpp and
// registration/src/ppf_registration.cpp), and what it means for this wrapper:
// - Features: PPFEstimation computes, for every ordered pair of model points (N^2 of them, the
//   pairs (i, i) as NaN), pcl::computePairFeatures: PFH's Darboux-frame triple f1 = an angle in
//   [-pi, pi], f2 and f3 = cosines in [-1, 1], f4 = the distance, plus Drost's alpha_m.
//   PPFHashMapSearch quantises f1..f3 with the same "angle" step (so f2, f3 are cut in cosine
//   units: about 10 bins of uneven angular width, fine near 90 degrees and coarse near 0 and 180)
//   and f4 with the distance step, into a std::unordered_multimap. Its hash XORs the four bin
//   indices shifted by 0..3 bits: the ~78,000 possible keys at our steps share under 500 hash
//   values, so every insert and every lookup walks a bucket of N^2 / 500 nodes. Building the map
//   for an 878-point model takes 100 to 200 s (offline, untimed in the benchmark), and lookups
//   dominate align().
// - PFH's features are symmetric (computePairFeatures swaps the pair to a canonical order), so a
//   scene pair also matches the model pair (j, i) of each (i, j) and votes for it with the
//   reference swapped: twice the votes of Drost's ordered features, half of them noise.
// - Scene search radius: each reference point is paired only with the scene points within HALF
//   the model diameter (the largest f4 of the model features), not the full diameter of Drost's
//   paper. Not configurable.
// - References: every k-th point of the target cloud in cloud order (k = sampling rate), not a
//   random subset. Each reference votes over (model point, alpha) and contributes exactly one
//   pose, the accumulator's maximum, with its vote count (zero votes included).
// - Clustering: poses sorted by votes join the first cluster whose FIRST pose is within both
//   thresholds; clusters are ranked by summed votes; the three best are averaged (translation
//   mean, quaternion mean renormalised) and align() returns only the best one. The quaternions
//   are summed without bringing them to one hemisphere (q and -q are the same rotation; Eigen's
//   matrix-to-quaternion picks either sign for turns beyond 120 degrees), so a cluster of such
//   turns can average to a wrong rotation; ICP repairs small errors only.
// - align() with an empty target dereferences results.front() of an empty list: we never call it
//   with fewer points than a part needs.
// - The alpha accumulator has floor(2 pi / step) columns but is indexed with
//   floor((alpha + pi) / step): see accumulatorSafeAngleStep.
#include <pcl/common/transforms.h>
#include <pcl/console/print.h>
#include <pcl/features/normal_3d_omp.h>
#include <pcl/features/ppf.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/ppf_registration.h>
#include <pcl/search/kdtree.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "binpick/core/error.hpp"
#include "binpick/core/stopwatch.hpp"

namespace binpick::bench {

namespace {

using PointN = pcl::PointNormal;
using CloudN = pcl::PointCloud<PointN>;
using SceneTree = pcl::search::KdTree<PointN>;

constexpr double kPi = 3.14159265358979323846;

float radians(float degrees) { return static_cast<float>(degrees * kPi / 180.0); }

// PCL sizes the alpha accumulator floor(2 pi / step) columns and indexes it with
// floor((alpha + pi) / step), where alpha (a float, wrapped into [-M_PI, M_PI]) reaches
// 3.1415925f. Both are computed in double from the float step. With step = float(12 degrees)
// (PCL's own default) 2 pi / step = 29.999997: 29 columns, and every vote with alpha in the last
// 12 degrees increments column 29, one past the end: undefined behaviour (in practice it lands in
// malloc padding, is never read, and those votes are lost). No float step gives exactly 30 safe
// columns: one with floor(2 pi / step) = 30 puts alpha = 3.1415925f in column 30, which would
// hit the next heap chunk's header. So we use the bin count nearest the requested step for which
// a float step exists with floor(2 pi / step) = bins and the largest alpha in column bins - 1:
// for 12 degrees that is 29 bins of 12.41 degrees (31 bins have no safe float either).
float accumulatorSafeAngleStep(float step_deg) {
  const double two_pi = 2.0 * kPi;
  const double largest_alpha = std::nextafter(static_cast<float>(kPi), 0.0f);  // < M_PI
  const auto fits = [&](double bins, float step) {
    return std::floor(two_pi / step) == bins && std::floor((largest_alpha + kPi) / step) < bins;
  };
  const double wanted = std::max(1.0, std::round(360.0 / step_deg));
  for (int offset = 0; offset <= 4; ++offset) {
    for (const double bins : {wanted - offset, wanted + offset}) {
      if (bins < 1.0) continue;
      float step = std::nextafter(static_cast<float>(two_pi / bins), 1.0f);
      for (int ulps = 0; ulps < 4; ++ulps, step = std::nextafter(step, 0.0f)) {
        if (fits(bins, step)) return step;
      }
    }
  }
  throw core::Error("pcl_ppf: no float angle step near the requested one is safe in PCL's accumulator");
}

// The prepared model as PCL points with normals (model frame).
CloudN::Ptr modelCloud(const estimation::PreparedModel& model) {
  auto cloud = std::make_shared<CloudN>();
  cloud->reserve(model.size());
  for (std::size_t i = 0; i < model.size(); ++i) {
    PointN p;
    p.getVector3fMap() = model.points[i];
    p.getNormalVector3fMap() = model.normals[i];
    p.curvature = 0.0f;
    cloud->push_back(p);
  }
  return cloud;
}

// All N^2 model pair features, hashed. N^2 PPFSignatures and as many hash nodes: about
// 70 bytes per pair, i.e. ~70 MB for a 1000-point model.
pcl::PPFHashMapSearch::Ptr buildHashMap(const CloudN::Ptr& model, float angle_step, float distance_step) {
  pcl::PPFEstimation<PointN, PointN, pcl::PPFSignature> estimation;
  estimation.setInputCloud(model);
  estimation.setInputNormals(model);
  auto features = std::make_shared<pcl::PointCloud<pcl::PPFSignature>>();
  estimation.compute(*features);
  auto search = std::make_shared<pcl::PPFHashMapSearch>(angle_step, distance_step);
  search->setInputFeatureCloud(features);
  return search;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr toPcl(const std::vector<Eigen::Vector3f>& points) {
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  cloud->reserve(points.size());
  for (const Eigen::Vector3f& p : points) cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  return cloud;
}

// Voxel-grid centroids of the cropped cloud, each with a normal fitted to the full-resolution
// cropped points within `radius`, turned towards the camera at the origin. Points whose
// neighbourhood is too small for a plane (PCL gives NaN) are dropped.
CloudN::Ptr sceneWithNormals(const std::vector<Eigen::Vector3f>& cropped, float leaf, float radius, int threads) {
  auto scene = std::make_shared<CloudN>();
  if (cropped.empty()) return scene;
  const auto full = toPcl(cropped);
  auto sub = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  pcl::VoxelGrid<pcl::PointXYZ> grid;
  grid.setInputCloud(full);
  grid.setLeafSize(leaf, leaf, leaf);
  grid.filter(*sub);

  pcl::NormalEstimationOMP<pcl::PointXYZ, pcl::Normal> estimation;
  estimation.setInputCloud(sub);
  estimation.setSearchSurface(full);
  estimation.setSearchMethod(std::make_shared<pcl::search::KdTree<pcl::PointXYZ>>());
  estimation.setRadiusSearch(radius);
  estimation.setViewPoint(0.0f, 0.0f, 0.0f);                                   // the camera: normals face it
  estimation.setNumberOfThreads(static_cast<unsigned>(std::max(0, threads)));  // 0: all processors
  pcl::PointCloud<pcl::Normal> normals;
  estimation.compute(normals);

  scene->reserve(sub->size());
  for (std::size_t i = 0; i < sub->size(); ++i) {
    if (!normals[i].getNormalVector3fMap().allFinite()) continue;
    PointN p;
    p.getVector3fMap() = (*sub)[i].getVector3fMap();
    p.getNormalVector3fMap() = normals[i].getNormalVector3fMap();
    p.curvature = normals[i].curvature;
    scene->push_back(p);
  }
  return scene;
}

// A float pose from PCL's 4x4 matrix, its rotation re-orthonormalised (PCL accumulates products
// of float matrices).
Eigen::Isometry3f toIsometry(const Eigen::Matrix4f& m) {
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.linear() = Eigen::Quaternionf(m.topLeftCorner<3, 3>()).normalized().toRotationMatrix();
  pose.translation() = m.topRightCorner<3, 1>();
  return pose;
}

CloudN::Ptr posedModel(const CloudN& model, const Eigen::Isometry3f& pose) {
  auto posed = std::make_shared<CloudN>();
  pcl::transformPointCloudWithNormals(model, *posed, pose.matrix());
  return posed;
}

// The posed model points facing the camera (normal towards the origin): the side a depth camera
// can see. ICP from all model points would drag the hidden side onto the visible surface.
CloudN::Ptr facingCamera(const CloudN& posed) {
  auto facing = std::make_shared<CloudN>();
  for (const PointN& p : posed) {
    if (p.getNormalVector3fMap().dot(-p.getVector3fMap()) > 0.0f) facing->push_back(p);
  }
  return facing;
}

}  // namespace

void PclPpfParams::validate() const {
  const auto positive = [](float v, const char* field) {
    if (!(v > 0.0f) || !std::isfinite(v)) throw core::Error(std::string("pcl_ppf params: ") + field + " must be > 0");
  };
  if (!(reference_fraction > 0.0f && reference_fraction <= 1.0f))
    throw core::Error("pcl_ppf params: reference_fraction must be in (0, 1]");
  if (!(angle_step_deg > 0.0f && angle_step_deg <= 180.0f))
    throw core::Error("pcl_ppf params: angle_step_deg must be in (0, 180]");
  positive(distance_step_ratio, "distance_step_ratio");
  positive(voxel_ratio, "voxel_ratio");
  positive(normal_radius_ratio, "normal_radius_ratio");
  positive(cluster_translation_ratio, "cluster_translation_ratio");
  positive(cluster_rotation_deg, "cluster_rotation_deg");
  if (icp_iterations < 0) throw core::Error("pcl_ppf params: icp_iterations must be >= 0");
  positive(icp_max_distance_ratio, "icp_max_distance_ratio");
  positive(support_distance_ratio, "support_distance_ratio");
  if (!(min_support >= 0.0f && min_support <= 1.0f)) throw core::Error("pcl_ppf params: min_support must be in [0, 1]");
  positive(removal_radius_ratio, "removal_radius_ratio");
}

struct PclPpfMethod::Impl {
  const estimation::PreparedModel* model = nullptr;
  int max_objects = 0;
  int threads = 0;
  PclPpfParams params;
  float step = 0.0f;        // d_dist, metres
  float angle_step = 0.0f;  // radians, accumulator-safe
  CloudN::Ptr model_cloud;
  pcl::PPFHashMapSearch::Ptr hash_map;  // read-only after construction: shared by all calls

  // Fewer remaining scene points than this cannot give a pose with min_support (each scene
  // point supports about one model point at equal subsampling): stop.
  std::size_t minScenePoints() const {
    const double needed = std::ceil(params.min_support * static_cast<double>(model->size()));
    return std::max<std::size_t>(3, static_cast<std::size_t>(needed));
  }

  Eigen::Isometry3f align(const CloudN::Ptr& scene, const SceneTree::Ptr& tree) const;
  Eigen::Isometry3f refine(const CloudN::Ptr& scene, const SceneTree::Ptr& tree, const Eigen::Isometry3f& coarse) const;
  float support(const CloudN& posed, const SceneTree& tree) const;
  CloudN::Ptr withoutExplained(const CloudN& scene, const CloudN::Ptr& posed) const;
};

// One PPFRegistration::align: the best pose cluster of the given scene points. A registration
// object per call, so concurrent detect() calls share nothing but the read-only hash map.
Eigen::Isometry3f PclPpfMethod::Impl::align(const CloudN::Ptr& scene, const SceneTree::Ptr& tree) const {
  pcl::PPFRegistration<PointN, PointN> registration;
  const auto rate = static_cast<unsigned>(std::max(1L, std::lround(1.0 / params.reference_fraction)));
  registration.setSceneReferencePointSamplingRate(rate);
  registration.setPositionClusteringThreshold(params.cluster_translation_ratio * model->diameter);
  registration.setRotationClusteringThreshold(radians(params.cluster_rotation_deg));
  registration.setSearchMethod(hash_map);
  registration.setInputSource(model_cloud);
  registration.setInputTarget(scene);              // builds PCL's own FLANN tree for the radius search
  registration.setSearchMethodTarget(tree, true);  // spares the base class a second tree
  CloudN aligned;
  registration.align(aligned);
  return toIsometry(registration.getFinalTransformation());
}

// Point-to-plane ICP of the camera-facing model points onto the scene points PPF was given. It
// moves the posed points, so the result is the correction times the coarse pose. We use PCL's
// symmetric objective (Rusinkiewicz 2019; model and scene normals): PCL's plain point-to-plane
// solves its 6x6 normal equations with an explicit inverse, which is singular, and gives NaN
// poses, whenever the part shows a single flat face; the symmetric variant solves with LDLT,
// which leaves the unconstrained directions alone. Without convergence (e.g. fewer than 3
// correspondences) or with a non-finite result the coarse pose stands.
Eigen::Isometry3f PclPpfMethod::Impl::refine(const CloudN::Ptr& scene, const SceneTree::Ptr& tree,
                                             const Eigen::Isometry3f& coarse) const {
  const CloudN::Ptr source = facingCamera(*posedModel(*model_cloud, coarse));
  if (params.icp_iterations == 0 || source->size() < 3) return coarse;
  pcl::IterativeClosestPointWithNormals<PointN, PointN> icp;
  icp.setUseSymmetricObjective(true);
  icp.setInputSource(source);
  icp.setInputTarget(scene);
  icp.setSearchMethodTarget(tree, true);
  icp.setMaxCorrespondenceDistance(params.icp_max_distance_ratio * step);
  icp.setMaximumIterations(params.icp_iterations);
  // Converged when an iteration moves less than 1e-3 step and turns less than 0.01 degree:
  // binpick's own ICP criteria (IcpParams). PCL compares the squared translation.
  icp.setTransformationEpsilon(static_cast<double>(1e-3f * step) * (1e-3f * step));
  icp.setTransformationRotationEpsilon(std::cos(0.01 * kPi / 180.0));
  CloudN moved;
  icp.align(moved);
  if (!icp.hasConverged()) return coarse;
  const Eigen::Isometry3f refined = toIsometry(icp.getFinalTransformation() * coarse.matrix());
  return refined.matrix().allFinite() ? refined : coarse;
}

// Share of all model points at the pose with a scene point within support_distance_ratio steps.
float PclPpfMethod::Impl::support(const CloudN& posed, const SceneTree& tree) const {
  const float reach = params.support_distance_ratio * step;
  pcl::Indices nearest(1);
  std::vector<float> distance_sq(1);
  std::size_t fitted = 0;
  for (const PointN& p : posed) {
    if (tree.nearestKSearch(p, 1, nearest, distance_sq) == 1 && distance_sq[0] <= reach * reach) ++fitted;
  }
  return posed.empty() ? 0.0f : static_cast<float>(fitted) / static_cast<float>(posed.size());
}

// The scene points farther than removal_radius_ratio steps from every posed model point.
CloudN::Ptr PclPpfMethod::Impl::withoutExplained(const CloudN& scene, const CloudN::Ptr& posed) const {
  pcl::KdTreeFLANN<PointN> model_tree;
  model_tree.setInputCloud(posed);
  const float radius = params.removal_radius_ratio * step;
  pcl::Indices nearest(1);
  std::vector<float> distance_sq(1);
  auto kept = std::make_shared<CloudN>();
  kept->reserve(scene.size());
  for (const PointN& p : scene) {
    const bool explained =
        model_tree.nearestKSearch(p, 1, nearest, distance_sq) == 1 && distance_sq[0] <= radius * radius;
    if (!explained) kept->push_back(p);
  }
  return kept;
}

PclPpfMethod::PclPpfMethod(const MethodSetup& setup, PclPpfParams params) : impl_(std::make_unique<Impl>()) {
  if (setup.model == nullptr || setup.model->size() < 2) throw core::Error("pcl_ppf: the setup needs a prepared model");
  if (setup.model->normals.size() != setup.model->size()) throw core::Error("pcl_ppf: model normals missing");
  params.validate();
  if (params.quiet_pcl && pcl::console::isVerbosityLevelEnabled(pcl::console::L_WARN)) {
    pcl::console::setVerbosityLevel(pcl::console::L_ERROR);
  }
  impl_->model = setup.model;
  impl_->max_objects = setup.max_objects;
  impl_->threads = setup.threads;
  impl_->params = params;
  impl_->step = setup.model->step;
  impl_->angle_step = accumulatorSafeAngleStep(params.angle_step_deg);
  impl_->model_cloud = modelCloud(*setup.model);
  impl_->hash_map = buildHashMap(impl_->model_cloud, impl_->angle_step, params.distance_step_ratio * impl_->step);
}

PclPpfMethod::~PclPpfMethod() = default;

std::string PclPpfMethod::name() const { return "pcl_ppf"; }

std::vector<Eigen::Isometry3f> PclPpfMethod::detect(const MethodInput& input) const { return detect(input, nullptr); }

// Our loop around PCL, which gives one pose per align(): find the best part, refine it, keep it,
// take its points out of the scene, and look again, until max_objects poses, too few points left,
// or a pose supported by under min_support of the model points.
std::vector<Eigen::Isometry3f> PclPpfMethod::detect(const MethodInput& input, PclPpfTimings* timings) const {
  PclPpfTimings local;
  PclPpfTimings& t = timings != nullptr ? *timings : local;
  t = PclPpfTimings{};
  std::vector<Eigen::Isometry3f> poses;
  if (input.cloud == nullptr) return poses;
  const Impl& im = *impl_;

  const core::Stopwatch normals;
  CloudN::Ptr remaining = sceneWithNormals(croppedPoints(input), im.params.voxel_ratio * im.step,
                                           im.params.normal_radius_ratio * im.step, im.threads);
  t.scene_points = remaining->size();
  t.normals = normals.elapsedMs();

  while (static_cast<int>(poses.size()) < im.max_objects && remaining->size() >= im.minScenePoints()) {
    auto tree = std::make_shared<SceneTree>();
    tree->setInputCloud(remaining);

    core::Stopwatch stage;  // started after the tree: building it is no stage's time
    const Eigen::Isometry3f coarse = im.align(remaining, tree);
    t.align += stage.lapMs();
    ++t.align_calls;
    if (!coarse.matrix().allFinite()) break;  // not seen; PCL would repeat it on the same points

    const Eigen::Isometry3f refined = im.refine(remaining, tree, coarse);
    t.icp += stage.lapMs();

    const CloudN::Ptr posed = posedModel(*im.model_cloud, refined);
    const bool supported = im.support(*posed, *tree) >= im.params.min_support;
    if (supported) {
      poses.push_back(refined);
      remaining = im.withoutExplained(*remaining, posed);
    }
    t.removal += stage.lapMs();
    if (!supported) break;  // the same points would give PCL the same pose again
  }
  return poses;
}

}  // namespace binpick::bench
