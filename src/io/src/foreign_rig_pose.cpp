// Rotations and translations read in the shapes other tools write, and board poses composed.
#include "foreign_rig_pose.hpp"

#include <Eigen/SVD>
#include <cmath>
#include <cstdio>

#include "binpick/core/error.hpp"

namespace binpick::io::detail {
namespace {

// Printing a rotation to 4 or more significant digits leaves it this close to orthonormal.
constexpr double kMaxRotationDeviation = 1e-3;
constexpr double kMaxViewAngleDeg = 2.0;
constexpr double kMaxViewBaselineShare = 0.1;

using Shape = std::vector<int>;

// The shapes of a single 3-vector: a list, a row, a column.
bool isVector3(const Shape& shape) { return shape == Shape{3} || shape == Shape{1, 3} || shape == Shape{3, 1}; }

// n 3-vectors: n x 3, n x 1 x 3, n x 3 x 1 (numpy's stack of column vectors), or a list of them.
bool isVector3List(const Shape& shape) {
  if (shape.size() == 2) return shape[1] == 3;
  return shape.size() == 3 && (shape[1] * shape[2] == 3) && (shape[1] == 1 || shape[2] == 1);
}

bool isMatrix3List(const Shape& shape) { return shape.size() == 3 && shape[1] == 3 && shape[2] == 3; }

std::string shapeName(const StoredNumbers& stored) { return stored.shapeText(); }

Eigen::Matrix3d matrixAt(const std::vector<double>& values, std::size_t first) {
  Eigen::Matrix3d m;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m(i, j) = values[first + 3 * i + j];
  }
  return m;
}

Eigen::Vector3d vectorAt(const std::vector<double>& values, std::size_t first) {
  return {values[first], values[first + 1], values[first + 2]};
}

Eigen::Matrix3d fromRotationVector(const Eigen::Vector3d& v) {
  const double angle = v.norm();
  if (!(angle > 0.0)) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, v / angle).toRotationMatrix();
}

double deviationFromRotation(const Eigen::Matrix3d& m) {
  return (m * m.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
}

bool isNearRotation(const Eigen::Matrix3d& m) {
  return deviationFromRotation(m) <= kMaxRotationDeviation && m.determinant() > 0.0;
}

Eigen::Matrix3d nearestRotation(const Eigen::Matrix3d& m) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d r = svd.matrixU() * svd.matrixV().transpose();
  if (r.determinant() < 0.0) {
    Eigen::Matrix3d flip = Eigen::Matrix3d::Identity();
    flip(2, 2) = -1.0;
    r = svd.matrixU() * flip * svd.matrixV().transpose();
  }
  return r;
}

Eigen::Matrix3d checkedRotation(const Eigen::Matrix3d& m) {
  if (isNearRotation(m)) return nearestRotation(m);
  char text[160];
  std::snprintf(text, sizeof text, "is not a rotation (R R^T differs from I by %.3g, determinant %.3g)",
                deviationFromRotation(m), m.determinant());
  throw core::Error(text);
}

double angleBetweenDeg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle() * 180.0 / M_PI;
}

}  // namespace

Eigen::Matrix3d rotationOf(const StoredNumbers& stored) {
  if (isVector3(stored.shape)) return fromRotationVector(vectorAt(stored.values, 0));
  if (stored.shape == Shape{3, 3} || stored.shape == Shape{9}) return checkedRotation(matrixAt(stored.values, 0));
  throw core::Error("must be a 3x3 rotation matrix or a 3-value rotation vector (got " + shapeName(stored) + ")");
}

std::vector<Eigen::Matrix3d> rotationsOf(const StoredNumbers& stored) {
  const Shape& shape = stored.shape;
  if (shape == Shape{3, 3} && isNearRotation(matrixAt(stored.values, 0))) return {rotationOf(stored)};
  if (isVector3(shape) || shape == Shape{9}) return {rotationOf(stored)};
  std::vector<Eigen::Matrix3d> rotations;
  if (isVector3List(shape)) {
    for (int view = 0; view < shape[0]; ++view)
      rotations.push_back(fromRotationVector(vectorAt(stored.values, 3 * view)));
    return rotations;
  }
  if (isMatrix3List(shape)) {
    for (int view = 0; view < shape[0]; ++view) {
      try {
        rotations.push_back(checkedRotation(matrixAt(stored.values, 9 * view)));
      } catch (const core::Error& e) {
        throw core::Error("view " + std::to_string(view) + " " + e.what());
      }
    }
    return rotations;
  }
  throw core::Error(
      "must hold one rotation (3x3 matrix or rotation vector) per view: n x 3 rotation vectors or n "
      "3x3 matrices (got " +
      shapeName(stored) + ")");
}

Eigen::Vector3d translationOf(const StoredNumbers& stored) {
  if (isVector3(stored.shape)) return vectorAt(stored.values, 0);
  throw core::Error("must hold 3 values (got " + shapeName(stored) + ")");
}

std::vector<Eigen::Vector3d> translationsOf(const StoredNumbers& stored) {
  if (isVector3(stored.shape)) return {translationOf(stored)};
  if (!isVector3List(stored.shape)) {
    throw core::Error("must hold one translation (3 values) per view: n x 3 (got " + shapeName(stored) + ")");
  }
  std::vector<Eigen::Vector3d> translations;
  for (int view = 0; view < stored.shape[0]; ++view) translations.push_back(vectorAt(stored.values, 3 * view));
  return translations;
}

Eigen::Isometry3d composeFromBoardViews(const BoardViews& camera, const BoardViews& projector) {
  const std::size_t views = camera.rotations.size();
  if (views == 0 || camera.translations.size() != views || projector.rotations.size() != views ||
      projector.translations.size() != views) {
    throw core::Error("the board poses differ in number of views (camera " + std::to_string(camera.rotations.size()) +
                      " rotations, " + std::to_string(camera.translations.size()) + " translations; projector " +
                      std::to_string(projector.rotations.size()) + " rotations, " +
                      std::to_string(projector.translations.size()) + " translations)");
  }
  // x_p = Rp Rc^T (x_c - tc) + tp in every view.
  std::vector<Eigen::Matrix3d> rotations(views);
  std::vector<Eigen::Vector3d> translations(views);
  Eigen::Matrix3d rotation_sum = Eigen::Matrix3d::Zero();
  Eigen::Vector3d translation_sum = Eigen::Vector3d::Zero();
  for (std::size_t v = 0; v < views; ++v) {
    rotations[v] = projector.rotations[v] * camera.rotations[v].transpose();
    translations[v] = projector.translations[v] - rotations[v] * camera.translations[v];
    rotation_sum += rotations[v];
    translation_sum += translations[v];
  }
  Eigen::Isometry3d mean = Eigen::Isometry3d::Identity();
  mean.linear() = nearestRotation(rotation_sum);
  mean.translation() = translation_sum / static_cast<double>(views);
  for (std::size_t v = 0; v < views; ++v) {
    const double angle = angleBetweenDeg(rotations[v], mean.linear());
    const double offset = (translations[v] - mean.translation()).norm() / mean.translation().norm();
    if (angle <= kMaxViewAngleDeg && offset <= kMaxViewBaselineShare) continue;
    char text[260];
    std::snprintf(text, sizeof text,
                  "the board poses do not compose into one rig: view %zu puts the projector %.2f degrees and %.0f%% of "
                  "the baseline from the mean of the %zu views (are both devices' poses of the same views, in the "
                  "same order?)",
                  v, angle, 100.0 * offset, views);
    throw core::Error(text);
  }
  return mean;
}

}  // namespace binpick::io::detail
