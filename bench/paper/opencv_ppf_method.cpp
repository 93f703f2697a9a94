#include "opencv_ppf_method.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/surface_matching.hpp>
#include <opencv2/surface_matching/ppf_helpers.hpp>
#include <unordered_map>

#include "binpick/core/error.hpp"
#include "binpick/core/stopwatch.hpp"

// How binpick's resolution is given to OpenCV 4.6 (read from modules/surface_matching/src):
//
// * trainModel(M) quantises M on a grid of (int)(1 / r) cells per axis of M's bounding box, r the
//   constructor's relativeSamplingStep, and quantises pair distances at r * diag(bbox(M)); the
//   constructor's relativeDistanceStep is stored but never used. We pass r = d_dist / diag(bbox):
//   the distance step is then exactly binpick's d_dist, and the grid cells (extent / (int)(1/r)
//   per axis, at most about d_dist) are no bigger than the spacing of binpick's model points,
//   which are already subsampled at d_dist, so OpenCV trains on (nearly) the same points.
// * match(S, ..., f, s) quantises the scene on a grid of (int)(1 / s) cells per axis of the
//   SCENE's bounding box, so cells are anisotropic: extent_axis / (int)(1 / s). We pass
//   s = d_dist / (longest extent of S): cells are d_dist along the longest axis (the bin's
//   length) and finer along the others (the pile's height above all), so OpenCV gets somewhat
//   more scene points than binpick's d_dist voxels: in its favour for accuracy, against it for
//   time. It then refers every (int)(1 / f)-th of the quantised points.
// * Pose clustering defaults are unusable in metres: the position threshold defaults to the
//   relative sampling step taken as an absolute distance (0.04 m for a ~0.1 m part would merge
//   neighbouring parts), and the rotation threshold to (360 / angle_step_in_radians) degrees
//   in radians, about 30 rad, i.e. no rotation test. We set both (see OpenCvPpfParams).
//
// Cost: training inserts every model pair into a hash table whose buckets are linked lists walked
// to the end on each insert, and matching walks the whole bucket of each scene pair. A part with
// big flat faces puts most of its pairs into a few buckets (binpick caps them, OpenCV does not),
// so both go quadratic: for the l_bracket at binpick's resolution (878 model points) training
// took 7-28 s and match() 130-225 s on a 20-part scene (2 cores).
//
// Scene normals: computeNormalsPC3d on all ~130k cropped points of a 20-part scene took ~1.3 s;
// on the half-step voxel centroids (~20k points) 0.1-0.16 s. OpenCV's own quantisation averages
// both into the same step-sized cells, so we pre-sample (OpenCvPpfParams::normal_voxel_ratio).
// The pre-sampled cloud with its normals is also ICP's scene.
//
// Threads: the Debian build of surface_matching is compiled without OpenMP (no libgomp, no GOMP
// symbols), so match(), the pose clustering and ICP run on one thread; only computeNormalsPC3d
// (FLANN kNN + cv::parallel_for_) uses cv::setNumThreads, which we set to setup.threads.

namespace binpick::bench {
namespace {

namespace ppf = cv::ppf_match_3d;

// cv::setNumThreads for one scope. OpenCV reads 0 as "no threads" and a negative value as "its
// default (all cores)", so setup.threads = 0 becomes -1.
class ScopedCvThreads {
 public:
  explicit ScopedCvThreads(int threads) : previous_(cv::getNumThreads()) {
    cv::setNumThreads(threads > 0 ? threads : -1);
  }
  ~ScopedCvThreads() { cv::setNumThreads(previous_); }
  ScopedCvThreads(const ScopedCvThreads&) = delete;
  ScopedCvThreads& operator=(const ScopedCvThreads&) = delete;

 private:
  int previous_;
};

// Points (and optionally normals) as the Nx3 / Nx6 CV_32F rows OpenCV's functions take.
cv::Mat toMat(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>* normals = nullptr) {
  cv::Mat mat(static_cast<int>(points.size()), normals ? 6 : 3, CV_32F);
  for (int i = 0; i < mat.rows; ++i) {
    float* row = mat.ptr<float>(i);
    for (int c = 0; c < 3; ++c) row[c] = points[i][c];
    if (normals) {
      for (int c = 0; c < 3; ++c) row[3 + c] = (*normals)[i][c];
    }
  }
  return mat;
}

// The per-axis extent of the bounding box, as OpenCV's computeBboxStd sees it.
Eigen::Vector3f boxExtent(const std::vector<Eigen::Vector3f>& points) {
  Eigen::Vector3f lo = points.front();
  Eigen::Vector3f hi = points.front();
  for (const Eigen::Vector3f& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return hi - lo;
}

// A voxel's integer coordinates packed into one key, 21 bits per axis: +-1e6 voxels, i.e. +-1 km
// at a 1 mm voxel.
uint64_t voxelKey(const Eigen::Vector3f& p, float voxel) {
  uint64_t key = 0;
  for (int c = 0; c < 3; ++c) {
    const auto cell = static_cast<int64_t>(std::floor(p[c] / voxel)) + (int64_t{1} << 20);
    key = (key << 21) | (static_cast<uint64_t>(cell) & 0x1FFFFFu);
  }
  return key;
}

// Centroids of the occupied cubic voxels of side `voxel`, in order of first occupation (so the
// result is deterministic).
std::vector<Eigen::Vector3f> voxelCentroids(const std::vector<Eigen::Vector3f>& points, float voxel) {
  struct Cell {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int count = 0;
  };
  std::unordered_map<uint64_t, std::size_t> index;
  std::vector<Cell> cells;
  index.reserve(points.size() / 4);
  for (const Eigen::Vector3f& p : points) {
    const auto [it, inserted] = index.emplace(voxelKey(p, voxel), cells.size());
    if (inserted) cells.emplace_back();
    Cell& cell = cells[it->second];
    cell.sum += p.cast<double>();
    ++cell.count;
  }
  std::vector<Eigen::Vector3f> centroids;
  centroids.reserve(cells.size());
  for (const Cell& cell : cells) centroids.push_back((cell.sum / cell.count).cast<float>());
  return centroids;
}

// The nearest rotation to a 3x3 block: OpenCV's cluster averages are means of unnormalised
// quaternions, and ICP composes many small steps, so the block need not be exactly orthonormal.
Eigen::Matrix3f nearestRotation(const Eigen::Matrix3d& m) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return (svd.matrixU() * d * svd.matrixV().transpose()).cast<float>();
}

Eigen::Isometry3f toIsometry(const cv::Matx44d& pose) {
  Eigen::Matrix3d r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r(i, j) = pose(i, j);
  }
  Eigen::Isometry3f t = Eigen::Isometry3f::Identity();
  t.linear() = nearestRotation(r);
  t.translation() =
      Eigen::Vector3f(static_cast<float>(pose(0, 3)), static_cast<float>(pose(1, 3)), static_cast<float>(pose(2, 3)));
  return t;
}

// match() averages each cluster's quaternions without normalising them (nor aligning their
// signs), so its rotations can be far from orthonormal (determinants down to ~0.4 measured);
// ICP would then start from a shrunken model. Replace each by the nearest rotation first.
void orthonormalise(std::vector<cv::ppf_match_3d::Pose3DPtr>& poses) {
  for (const cv::ppf_match_3d::Pose3DPtr& pose : poses) {
    const Eigen::Isometry3f t = toIsometry(pose->pose);
    cv::Matx44d fixed = cv::Matx44d::eye();
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) fixed(i, j) = t.linear()(i, j);
      fixed(i, 3) = pose->pose(i, 3);
    }
    pose->updatePose(fixed);
  }
}

}  // namespace

void OpenCvPpfParams::validate() const {
  const std::string owner = "OpenCvPpfParams";
  core::requireField(reference_fraction > 0.0 && reference_fraction <= 1.0, owner, "reference_fraction", "in (0, 1]",
                     reference_fraction);
  core::requireField(num_angles >= 4, owner, "num_angles", ">= 4", num_angles);
  core::requireField(cluster_translation_ratio > 0.0, owner, "cluster_translation_ratio", "> 0",
                     cluster_translation_ratio);
  core::requireField(cluster_rotation_deg > 0.0 && cluster_rotation_deg <= 180.0, owner, "cluster_rotation_deg",
                     "in (0, 180]", cluster_rotation_deg);
  core::requireField(normal_voxel_ratio >= 0.0, owner, "normal_voxel_ratio", ">= 0", normal_voxel_ratio);
  core::requireField(normal_neighbours >= 3, owner, "normal_neighbours", ">= 3", normal_neighbours);
  core::requireField(icp_iterations >= 0, owner, "icp_iterations", ">= 0 (0: no ICP)", icp_iterations);
  core::requireField(icp_tolerance > 0.0f, owner, "icp_tolerance", "> 0", icp_tolerance);
  core::requireField(icp_rejection_scale >= 0.0f, owner, "icp_rejection_scale", ">= 0 (0: off)", icp_rejection_scale);
  core::requireField(icp_levels >= 1, owner, "icp_levels", ">= 1", icp_levels);
}

struct OpenCvPpfMethod::Trained {
  ppf::PPF3DDetector detector;
  cv::Mat model;  // Nx6 model points and normals, the ICP's source cloud

  Trained(double relative_sampling_step, double num_angles)
      : detector(relative_sampling_step, relative_sampling_step, num_angles) {}
};

OpenCvPpfMethod::OpenCvPpfMethod(const MethodSetup& setup, OpenCvPpfParams params) : setup_(setup), params_(params) {
  params_.validate();
  const estimation::PreparedModel* model = setup_.model;
  if (model == nullptr || model->points.size() < 2 || model->normals.size() != model->points.size()) {
    throw core::Error("OpenCvPpfMethod: needs a prepared model with points and normals");
  }
  // Distance step = relative step * diag(bbox(model)) = d_dist (see the comment at the top).
  const double relative_step = model->step / boxExtent(model->points).norm();
  trained_ = std::make_unique<Trained>(relative_step, params_.num_angles);
  trained_->model = toMat(model->points, &model->normals);
  trained_->detector.trainModel(trained_->model);
  constexpr double kRadPerDeg = 3.14159265358979323846 / 180.0;
  trained_->detector.setSearchParams(params_.cluster_translation_ratio * model->diameter,
                                     params_.cluster_rotation_deg * kRadPerDeg, params_.weighted_clustering);
}

OpenCvPpfMethod::~OpenCvPpfMethod() = default;

std::string OpenCvPpfMethod::name() const { return "opencv_ppf"; }

OpenCvPpfMethod::Timing OpenCvPpfMethod::lastTiming() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return timing_;
}

std::vector<Eigen::Isometry3f> OpenCvPpfMethod::detect(const MethodInput& input) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  timing_ = {};
  if (input.cloud == nullptr || setup_.max_objects <= 0) return {};
  const ScopedCvThreads threads(setup_.threads);
  core::Stopwatch stage;  // "normals": cropping, pre-sampling and computeNormalsPC3d
  std::vector<Eigen::Vector3f> points = croppedPoints(input);
  const float step = setup_.model->step;
  if (params_.normal_voxel_ratio > 0.0) {
    points = voxelCentroids(points, static_cast<float>(params_.normal_voxel_ratio) * step);
  }
  timing_.normal_points = points.size();
  // Too few points for the normals' kNN, or a flat bounding box: OpenCV's quantisation divides by
  // each axis's extent, so a zero extent would make NaN cell indices.
  if (points.size() < static_cast<std::size_t>(params_.normal_neighbours)) return {};
  const Eigen::Vector3f extent = boxExtent(points);
  if (!(extent.minCoeff() > 0.0f)) return {};

  cv::Mat scene;
  ppf::computeNormalsPC3d(toMat(points), scene, params_.normal_neighbours, true,
                          cv::Vec3f(0.0f, 0.0f, 0.0f));  // flip towards the camera
  timing_.normals = stage.lapMs();

  std::vector<ppf::Pose3DPtr> poses;
  // Grid cells of d_dist along the scene's longest axis (see the comment at the top).
  const double relative_scene_step = std::min(1.0, static_cast<double>(step) / extent.maxCoeff());
  trained_->detector.match(scene, poses, params_.reference_fraction, relative_scene_step);
  timing_.match = stage.lapMs();

  // OpenCV returns the clusters by votes; refine the best max_objects, as binpick's Drost does.
  if (poses.size() > static_cast<std::size_t>(setup_.max_objects)) poses.resize(setup_.max_objects);
  orthonormalise(poses);
  ppf::ICP icp(params_.icp_iterations, params_.icp_tolerance, params_.icp_rejection_scale, params_.icp_levels);
  if (!poses.empty() && params_.icp_iterations > 0) {
    icp.registerModelToScene(trained_->model, scene, poses);
  }
  if (params_.order_by_residual) {
    const auto by_residual = [](const ppf::Pose3DPtr& a, const ppf::Pose3DPtr& b) { return a->residual < b->residual; };
    std::stable_sort(poses.begin(), poses.end(), by_residual);
  }
  timing_.icp = stage.lapMs();

  std::vector<Eigen::Isometry3f> result;
  result.reserve(poses.size());
  for (const ppf::Pose3DPtr& pose : poses) result.push_back(toIsometry(pose->pose));
  return result;
}

}  // namespace binpick::bench
