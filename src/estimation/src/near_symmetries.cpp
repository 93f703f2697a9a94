#include "near_symmetries.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "kdtree.hpp"

namespace binpick::estimation {
namespace {

constexpr int kRegistrationIterations = 30;
constexpr float kMatchDistanceInSteps = 1.0f;  // a turned point overlaps the model within this
constexpr float kMinOverlap = 0.5f;            // less: another outline, not worth a refinement
constexpr float kSymmetricOverlap = 0.98f;     // more: a true symmetry, nothing to decide

// Point-to-point ICP of the model onto itself from `start`; the share of turned points that end up
// within a step of a model point.
float registerOntoItself(const PreparedModel& model, const KdTree& tree, Eigen::Isometry3f& turn) {
  const float gate_sq = 4.0f * model.step * model.step;
  const float match_sq = kMatchDistanceInSteps * kMatchDistanceInSteps * model.step * model.step;
  Eigen::Matrix3Xf from(3, model.size()), to(3, model.size());
  for (int it = 0; it < kRegistrationIterations; ++it) {
    Eigen::Index pairs = 0;
    for (const Eigen::Vector3f& p : model.points) {
      const Eigen::Vector3f q = turn * p;
      const auto [nearest, distance_sq] = tree.nearest(q);
      if (nearest < 0 || distance_sq > gate_sq) continue;
      from.col(pairs) = q;
      to.col(pairs) = model.points[static_cast<std::size_t>(nearest)];
      ++pairs;
    }
    if (pairs < 3) return 0.0f;
    const Eigen::Matrix4f step = Eigen::umeyama(from.leftCols(pairs), to.leftCols(pairs), false);
    turn = Eigen::Isometry3f(step) * turn;
  }
  std::size_t overlapping = 0;
  for (const Eigen::Vector3f& p : model.points) overlapping += tree.nearest(turn * p).second <= match_sq ? 1 : 0;
  return static_cast<float>(overlapping) / static_cast<float>(model.size());
}

}  // namespace

std::vector<Eigen::Isometry3f> nearSymmetries(const PreparedModel& model) {
  if (model.size() < 3) return {};
  Eigen::Matrix3f scatter = Eigen::Matrix3f::Zero();
  for (const Eigen::Vector3f& p : model.points) scatter += (p - model.centre) * (p - model.centre).transpose();
  const Eigen::Matrix3f axes = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f>(scatter).eigenvectors();
  const KdTree tree(model.points);

  std::vector<Eigen::Isometry3f> turns;
  for (int a = 0; a < 3; ++a) {
    for (int quarters = 1; quarters <= 3; ++quarters) {
      Eigen::Isometry3f turn = Eigen::Isometry3f::Identity();
      turn.linear() = Eigen::AngleAxisf(static_cast<float>(quarters * M_PI / 2.0), axes.col(a)).toRotationMatrix();
      turn.translation() = model.centre - turn.linear() * model.centre;  // about the centroid
      const float overlap = registerOntoItself(model, tree, turn);
      if (overlap >= kMinOverlap && overlap < kSymmetricOverlap) turns.push_back(turn);
    }
  }
  return turns;
}

}  // namespace binpick::estimation
