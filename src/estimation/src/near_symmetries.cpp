#include "binpick/estimation/near_symmetries.hpp"

#include "binpick/estimation/model.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "kdtree.hpp"
#include "point_ops.hpp"
#include "voxel_grid.hpp"

namespace binpick::estimation {
namespace {

constexpr int kRegistrationIterations = 30;
constexpr float kMatchDistanceInSteps = 1.0f;  // a turned point overlaps the model within this
constexpr float kMinOverlap = 0.5f;            // less: another outline, not worth a refinement
constexpr float kSymmetricOverlap = 0.98f;     // more: a true symmetry, nothing to decide
constexpr int kSlideSamples = 256;             // model points that score a slide
constexpr float kSlideStepInSteps = 2.0f;      // the slide search's grid, in d_dist ...
constexpr int kMaxSlidesEachWay = 8;           // ... coarser when a fine sampling would need more
constexpr float kMinNormalCosine = 0.5f;       // a point on the other face of a plate does not count
// Closer than this and a step: the same twin.
constexpr float kSameTurnRad = 5.0f * static_cast<float>(M_PI / 180.0);

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
    // Eigen's umeyama compiled on its own makes GCC 12 warn (-Warray-bounds: a 4-float load from
    // its 3-float mean, on a path for 4 or more rows it cannot rule out). Inlined whole here
    // (flatten), the 3 rows are known and the warning goes; the arithmetic is the same.
    const auto fitStep = [&]() __attribute__((flatten)) {
      return Eigen::umeyama(from.leftCols(pairs), to.leftCols(pairs), false);
    };
    const Eigen::Matrix4f step = fitStep();
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

// The model's extent along each of its principal axes (the columns of `axes`).
Eigen::Vector3f principalExtents(const PreparedModel& model, const Eigen::Matrix3f& axes) {
  Eigen::Vector3f low = Eigen::Vector3f::Constant(std::numeric_limits<float>::max()), high = -low;
  for (const Eigen::Vector3f& p : model.points) {
    const Eigen::Vector3f q = axes.transpose() * (p - model.centre);
    low = low.cwiseMin(q);
    high = high.cwiseMax(q);
  }
  return high - low;
}

// The spacing of the slide search's grid: 2 d_dist, or coarser where the model spans more than
// kMaxSlidesEachWay of those each way from its centre (a fine sampling_ratio), so that the
// search stays at most 17^3 slides.
float slideSpacing(const PreparedModel& model, const Eigen::Vector3f& extents) {
  return std::max(kSlideStepInSteps * model.step, extents.maxCoeff() / (2.0f * kMaxSlidesEachWay));
}

// Slides `turn` over a grid of offsets along the principal axes, as far as the model reaches, to
// where most of a sample of turned points land on a model point facing the same way (ties: the
// shortest slide). `grid` (voxels of half the spacing) answers "a model point near here" in O(1).
void slideToMostOverlap(const PreparedModel& model, const SceneVoxelGrid& grid, const Eigen::Matrix3f& axes,
                        const Eigen::Vector3f& extents, Eigen::Isometry3f& turn) {
  const std::size_t stride = std::max<std::size_t>(1, model.size() / kSlideSamples);
  std::vector<Eigen::Vector3f> points, normals;
  for (std::size_t k = 0; k < model.size(); k += stride) {
    points.push_back(turn * model.points[k]);
    normals.push_back(turn.linear() * model.normals[k]);
  }
  const float spacing = slideSpacing(model, extents);
  const Eigen::Vector3i reach = (extents / (2.0f * spacing)).array().ceil().cast<int>();
  int most = -1;
  Eigen::Vector3f best = Eigen::Vector3f::Zero();
  for (int i = -reach.x(); i <= reach.x(); ++i) {
    for (int j = -reach.y(); j <= reach.y(); ++j) {
      for (int k = -reach.z(); k <= reach.z(); ++k) {
        const Eigen::Vector3f slide = axes * (spacing * Eigen::Vector3f(i, j, k));
        int overlap = 0;
        for (std::size_t n = 0; n < points.size(); ++n) {
          const int32_t m = grid.at(points[n] + slide);
          overlap += m != SceneVoxelGrid::kEmpty && normals[n].dot(model.normals[m]) >= kMinNormalCosine;
        }
        if (overlap > most || (overlap == most && slide.norm() < best.norm())) most = overlap, best = slide;
      }
    }
  }
  turn.pretranslate(best);
}

// Whether `difference` (a model-frame transform) is one of the part's own turns (ModelSymmetry):
// about its axis through the origin by a multiple of 360/N degrees, or by any angle when revolved.
bool isOwnTurn(const Eigen::Isometry3f& difference, const PreparedModel& model) {
  const ModelSymmetry& symmetry = model.symmetry;
  if (symmetry.turns == 1 || difference.translation().norm() >= model.step) return false;
  const Eigen::AngleAxisf turn(difference.linear());
  if (turn.angle() < kSameTurnRad) return true;
  if (std::abs(turn.axis().dot(symmetry.axis)) < std::cos(kSameTurnRad)) return false;
  if (symmetry.turns == 0) return true;
  const float period = 2.0f * static_cast<float>(M_PI) / static_cast<float>(symmetry.turns);
  const float off = std::fmod(turn.angle(), period);
  return std::min(off, period - off) < kSameTurnRad;
}

// Two twins are one when they nearly coincide, or differ by one of the part's own turns: the
// pose turned either way shows the same.
bool sameTwin(const Eigen::Isometry3f& a, const Eigen::Isometry3f& b, const PreparedModel& model) {
  const float angle = Eigen::AngleAxisf(a.linear().transpose() * b.linear()).angle();
  const bool coincide = angle < kSameTurnRad && (a * model.centre - b * model.centre).norm() < model.step;
  return coincide || isOwnTurn(b.inverse() * a, model);
}

// Registers `turn` onto the model; true when the result is a near-symmetry (not another outline,
// not a true symmetry).
bool registeredNearSymmetry(const PreparedModel& model, const KdTree& tree, Eigen::Isometry3f& turn) {
  const float overlap = registerOntoItself(model, tree, turn);
  orthonormalise(turn);
  return overlap >= kMinOverlap && overlap < kSymmetricOverlap;
}

}  // namespace

NearSymmetries nearSymmetries(const PreparedModel& model) {
  if (model.size() < 3) return {};
  Eigen::Matrix3f scatter = Eigen::Matrix3f::Zero();
  for (const Eigen::Vector3f& p : model.points) scatter += (p - model.centre) * (p - model.centre).transpose();
  const Eigen::Matrix3f axes = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f>(scatter).eigenvectors();
  const KdTree tree(model.points);

  const Eigen::Vector3f extents = principalExtents(model, axes);
  const SceneVoxelGrid grid(model.points, 0.5f * slideSpacing(model, extents));

  NearSymmetries twins;
  std::vector<Eigen::Isometry3f> slid;
  for (const Eigen::Matrix3f& rotation : boxRotations()) {
    Eigen::Isometry3f turn = Eigen::Isometry3f::Identity();
    turn.linear() = axes * rotation * axes.transpose();                // in the principal frame
    turn.translation() = model.centre - turn.linear() * model.centre;  // about the centroid
    Eigen::Isometry3f slid_turn = turn;
    slideToMostOverlap(model, grid, axes, extents, slid_turn);
    const auto same = [&](const Eigen::Isometry3f& kept) { return sameTwin(kept, turn, model); };
    if (registeredNearSymmetry(model, tree, turn) && std::none_of(twins.turned.begin(), twins.turned.end(), same)) {
      twins.turned.push_back(turn);
    }
    if (registeredNearSymmetry(model, tree, slid_turn)) slid.push_back(slid_turn);
  }
  for (const Eigen::Isometry3f& turn : slid) {
    const auto same = [&](const Eigen::Isometry3f& kept) { return sameTwin(kept, turn, model); };
    if (std::none_of(twins.turned.begin(), twins.turned.end(), same) &&
        std::none_of(twins.slid.begin(), twins.slid.end(), same)) {
      twins.slid.push_back(turn);
    }
  }
  return twins;
}

}  // namespace binpick::estimation
