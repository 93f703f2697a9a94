#include "near_symmetries.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>

#include "kdtree.hpp"
#include "point_ops.hpp"

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

// The 23 turns that map a box onto itself but for the identity: quarter and half turns about its
// axes, half turns about the diagonals of its faces, third turns about its body diagonals. A part
// on one face may pass for itself turned by any of them when two of its sides are alike in size
// (a 60 x 30 x 35 housing shows a 60 x 30 or a 60 x 35 rectangle).
std::vector<Eigen::Matrix3f> boxRotations() {
  std::vector<Eigen::Matrix3f> rotations;
  std::array<int, 3> order{0, 1, 2};
  do {
    for (int signs = 0; signs < 8; ++signs) {
      Eigen::Matrix3f r = Eigen::Matrix3f::Zero();
      for (int row = 0; row < 3; ++row) r(row, order[row]) = (signs >> row & 1) ? -1.0f : 1.0f;
      if (r.determinant() > 0.0f && !r.isIdentity()) rotations.push_back(r);
    }
  } while (std::next_permutation(order.begin(), order.end()));
  return rotations;
}

}  // namespace

std::vector<Eigen::Isometry3f> nearSymmetries(const PreparedModel& model) {
  if (model.size() < 3) return {};
  Eigen::Matrix3f scatter = Eigen::Matrix3f::Zero();
  for (const Eigen::Vector3f& p : model.points) scatter += (p - model.centre) * (p - model.centre).transpose();
  const Eigen::Matrix3f axes = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f>(scatter).eigenvectors();
  const KdTree tree(model.points);

  std::vector<Eigen::Isometry3f> turns;
  for (const Eigen::Matrix3f& rotation : boxRotations()) {
    Eigen::Isometry3f turn = Eigen::Isometry3f::Identity();
    turn.linear() = axes * rotation * axes.transpose();                   // in the principal frame
    turn.translation() = model.centre - turn.linear() * model.centre;  // about the centroid
    const float overlap = registerOntoItself(model, tree, turn);
    orthonormalise(turn);
    if (overlap >= kMinOverlap && overlap < kSymmetricOverlap) turns.push_back(turn);
  }
  return turns;
}

}  // namespace binpick::estimation
