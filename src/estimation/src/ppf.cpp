#include "binpick/estimation/ppf.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "binpick/core/error.hpp"

namespace binpick::estimation {
namespace {

// atan2 form of the angle between two vectors: accurate near 0 and pi, where acos is not.
float angleBetween(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

int binOf(float value, float step, int bins) {
  const int bin = static_cast<int>(value / step);
  return bin < 0 ? 0 : (bin >= bins ? bins - 1 : bin);
}

}  // namespace

PointPairFeature computeFeature(const Eigen::Vector3f& p_i, const Eigen::Vector3f& n_i, const Eigen::Vector3f& p_j,
                                const Eigen::Vector3f& n_j) {
  const Eigen::Vector3f d = p_j - p_i;
  PointPairFeature f;
  f.distance = d.norm();
  f.angle_ni_d = angleBetween(n_i, d);
  f.angle_nj_d = angleBetween(n_j, d);
  f.angle_ni_nj = angleBetween(n_i, n_j);
  return f;
}

PointPairFeature computeBoundaryFeature(const Eigen::Vector3f& p_i, const Eigen::Vector3f& n_i,
                                        const Eigen::Vector3f& b_j, const Eigen::Vector3f& l_j) {
  constexpr float kPi = static_cast<float>(M_PI);
  const auto folded = [&](float angle) { return std::min(angle, kPi - angle); };
  const Eigen::Vector3f d = b_j - p_i;
  PointPairFeature f;
  f.distance = d.norm();
  f.angle_ni_d = angleBetween(n_i, d);
  f.angle_nj_d = folded(angleBetween(l_j, d));
  f.angle_ni_nj = folded(angleBetween(n_i, l_j));
  return f;
}

PpfQuantizer::PpfQuantizer(float distance_step, float angle_step, float max_distance)
    : distance_step_(distance_step), angle_step_(angle_step), max_distance_(max_distance) {
  if (!(distance_step > 0.0f) || !(angle_step > 0.0f) || !(max_distance > 0.0f) || !std::isfinite(distance_step) ||
      !std::isfinite(max_distance)) {
    throw core::Error("PpfQuantizer: distance step, angle step and maximum distance must be positive");
  }
  if (max_distance / distance_step > 10000.0f || angle_step < 0.01f) {
    throw core::Error("PpfQuantizer: steps too fine (more than 10000 distance bins or < 0.01 rad)");
  }
  distance_bins_ = static_cast<int>(max_distance / distance_step) + 1;
  angle_bins_ = static_cast<int>(std::ceil(static_cast<float>(M_PI) / angle_step));
  alpha_bins_ = static_cast<int>(std::ceil(kTwoPi / angle_step));
  alpha_bins_per_radian_ = static_cast<float>(alpha_bins_) / kTwoPi;
  key_count_ = static_cast<int64_t>(distance_bins_) * angle_bins_ * angle_bins_ * angle_bins_;
  for (int k = 1; k < angle_bins_; ++k) border_cosines_.push_back(std::cos(static_cast<float>(k) * angle_step));
  if (key_count_ > (int64_t{1} << 28)) {
    throw core::Error("PpfQuantizer: " + std::to_string(key_count_) +
                      " feature bins is too many; use a coarser distance or angle step");
  }
}

int64_t PpfQuantizer::key(const PointPairFeature& f) const {
  if (!(f.distance <= max_distance_)) return -1;
  const int64_t d = binOf(f.distance, distance_step_, distance_bins_);
  const int64_t a1 = binOf(f.angle_ni_d, angle_step_, angle_bins_);
  const int64_t a2 = binOf(f.angle_nj_d, angle_step_, angle_bins_);
  const int64_t a3 = binOf(f.angle_ni_nj, angle_step_, angle_bins_);
  return ((d * angle_bins_ + a1) * angle_bins_ + a2) * angle_bins_ + a3;
}

int PpfQuantizer::alphaBin(float alpha) const {
  float wrapped = std::fmod(alpha, kTwoPi);
  if (wrapped < 0.0f) wrapped += kTwoPi;
  return binOf(wrapped, kTwoPi / static_cast<float>(alpha_bins_), alpha_bins_);
}

float PpfQuantizer::alphaBinCentre(int bin) const {
  return (static_cast<float>(bin) + 0.5f) * kTwoPi / static_cast<float>(alpha_bins_);
}

Eigen::Isometry3f referenceFrame(const Eigen::Vector3f& p_ref, const Eigen::Vector3f& n_ref) {
  // FromTwoVectors handles n_ref == -x (it picks a perpendicular axis for the half turn).
  const Eigen::Quaternionf q = Eigen::Quaternionf::FromTwoVectors(n_ref, Eigen::Vector3f::UnitX());
  Eigen::Isometry3f T = Eigen::Isometry3f::Identity();
  T.linear() = q.toRotationMatrix();
  T.translation() = -(T.linear() * p_ref);
  return T;
}

Eigen::Isometry3f poseFromLocalCoordinate(const Eigen::Isometry3f& T_s, const Eigen::Isometry3f& T_m, float alpha) {
  const Eigen::Isometry3f Rx(Eigen::AngleAxisf(alpha, Eigen::Vector3f::UnitX()));
  return T_s.inverse() * Rx * T_m;
}

}  // namespace binpick::estimation
