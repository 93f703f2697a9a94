#pragma once
// Internal point-cloud operations shared by model and scene preparation.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

#include "binpick/core/thread_count.hpp"
#include "binpick/io/point_cloud.hpp"

namespace binpick::estimation {

// The pose with its rotation made orthonormal again: float compositions (ICP steps, a pose times a
// near-symmetry) drift by 1e-5 after a few dozen, more than a pose read back from JSON may have.
inline void orthonormalise(Eigen::Isometry3f& pose) {
  pose.linear() = Eigen::Quaternionf(pose.linear()).normalized().toRotationMatrix();
}

// Largest distance between two points, exact up to ~1% (a coarse grid keeps it O(n) for large
// clouds before the pairwise search).
float approximateDiameter(const std::vector<Eigen::Vector3f>& points);

// One representative per occupied voxel of side `step` (the point nearest the voxel's centroid).
// With normals and cluster_angle > 0, points of one voxel whose normals differ by more than the
// angle are kept apart (both sides of a thin wall survive). Returns indices into `points`.
std::vector<uint32_t> voxelSubsample(const std::vector<Eigen::Vector3f>& points,
                                     const std::vector<Eigen::Vector3f>* normals, float step, float cluster_angle);

// Accumulates neighbours of a point; the normal is the eigenvector of the smallest eigenvalue of
// their covariance (a plane fit), or nothing when there are too few or they are degenerate.
class PlaneFit {
 public:
  void add(const Eigen::Vector3f& p);
  std::size_t count() const { return count_; }
  std::optional<Eigen::Vector3f> normal(std::size_t min_neighbours) const;

 private:
  Eigen::Vector3d sum_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sum_outer_ = Eigen::Matrix3d::Zero();
  std::size_t count_ = 0;
};

}  // namespace binpick::estimation
