#pragma once
// Point pair features (Drost et al. 2010; Li & Hashimoto 2018 eq. 1), their quantisation and the
// local frames used by the voting scheme (eq. 2). Pure functions: thread-safe.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace binpick::estimation {

// F(m_i, m_j) = (|d|, angle(n_i, d), angle(n_j, d), angle(n_i, n_j)), d = m_j - m_i (eq. 1).
struct PointPairFeature {
  float distance = 0.0f;
  float angle_ni_d = 0.0f;   // radians in [0, pi]
  float angle_nj_d = 0.0f;   // radians in [0, pi]
  float angle_ni_nj = 0.0f;  // radians in [0, pi]
};

PointPairFeature computeFeature(const Eigen::Vector3f& p_i, const Eigen::Vector3f& n_i, const Eigen::Vector3f& p_j,
                                const Eigen::Vector3f& n_j);

// Surface-to-boundary feature (Choi et al. 2012, S2B): a surface point with its normal n_i paired
// with a boundary point b_j whose line direction l_j has no sign. The same four components as
// eq. 1 with l_j in place of n_j; the angles to l_j are folded into [0, pi/2].
PointPairFeature computeBoundaryFeature(const Eigen::Vector3f& p_i, const Eigen::Vector3f& n_i,
                                        const Eigen::Vector3f& b_j, const Eigen::Vector3f& l_j);

// Discretisation of features into hash keys and of the in-plane angle alpha into bins.
class PpfQuantizer {
 public:
  // distance_step: metres (or the model unit); angle_step: radians; max_distance: the model
  // diameter, beyond which pairs are never hashed.
  PpfQuantizer(float distance_step, float angle_step, float max_distance);

  // Key of a feature, or -1 when the pair is longer than max_distance.
  int64_t key(const PointPairFeature& f) const;
  // key(computeFeature(p_i, n_i, p_j, n_j)) without the angles, for the table and the voting: an
  // angle's bin is the number of bin borders whose cosine its own cosine does not exceed. It
  // agrees with the angle's bin except where float rounding puts the angle on the other side of a
  // border (within about 1e-6 rad). Three atan2 per pair were a third of the voting's time.
  // Normals need not have unit length; a zero one, like a zero distance, gives the angle 0.
  int64_t pairKey(const Eigen::Vector3f& p_i, const Eigen::Vector3f& n_i, const Eigen::Vector3f& p_j,
                  const Eigen::Vector3f& n_j) const {
    const Eigen::Vector3f d = p_j - p_i;
    const float distance = d.norm(), length_i = n_i.norm(), length_j = n_j.norm();
    return keyOfCosines(distance, n_i.dot(d) / (length_i * distance), n_j.dot(d) / (length_j * distance),
                        n_i.dot(n_j) / (length_i * length_j));
  }
  // key(computeBoundaryFeature(p_i, n_i, b_j, l_j)) the same way: an angle folded into [0, pi/2]
  // has the cosine's magnitude for its cosine.
  int64_t boundaryPairKey(const Eigen::Vector3f& p_i, const Eigen::Vector3f& n_i, const Eigen::Vector3f& b_j,
                          const Eigen::Vector3f& l_j) const {
    const Eigen::Vector3f d = b_j - p_i;
    const float distance = d.norm(), length_i = n_i.norm(), length_j = l_j.norm();
    return keyOfCosines(distance, n_i.dot(d) / (length_i * distance), std::abs(l_j.dot(d)) / (length_j * distance),
                        std::abs(n_i.dot(l_j)) / (length_i * length_j));
  }
  int64_t keyCount() const { return key_count_; }

  // Bin of an angle; any real angle is wrapped into [0, 2*pi) first, so alpha is binned over
  // one turn (a known defect elsewhere is to bin the difference of two angles over 4*pi).
  int alphaBin(float alpha) const;
  // The voting's hot path: alpha = a - b of two angles in [-pi, pi], so one turn of wrapping
  // suffices (no fmod). Branch-free: the sign of alpha is a coin toss per pair, and a mispredicted
  // branch here cost more than the rest of the vote.
  int alphaBinOfDifference(float a, float b) const {
    float alpha = a - b;
    alpha += kTwoPi * static_cast<float>(alpha < 0.0f);
    const int bin = static_cast<int>(alpha * alpha_bins_per_radian_);
    return std::min(bin, alpha_bins_ - 1);
  }
  int alphaBinCount() const { return alpha_bins_; }
  float alphaBinCentre(int bin) const;

  float distanceStep() const { return distance_step_; }
  float angleStep() const { return angle_step_; }
  float maxDistance() const { return max_distance_; }

 private:
  int64_t keyOfCosines(float distance, float cos_ni_d, float cos_nj_d, float cos_ni_nj) const {
    if (!(distance <= max_distance_)) return -1;
    const int64_t bin_d = std::min(static_cast<int>(distance / distance_step_), distance_bins_ - 1);
    const int64_t a1 = angleBinOfCosine(cos_ni_d), a2 = angleBinOfCosine(cos_nj_d);
    return ((bin_d * angle_bins_ + a1) * angle_bins_ + a2) * angle_bins_ + angleBinOfCosine(cos_ni_nj);
  }
  // floor(angle / step) from cos(angle): the angle reaches border k * step exactly when its
  // cosine is at most cos(k * step). NaN (0/0) reaches none: bin 0, as atan2(0, 0) = 0 gives.
  int angleBinOfCosine(float cosine) const {
    int bin = 0;
    for (float border : border_cosines_) bin += static_cast<int>(cosine <= border);
    return bin;
  }

  float distance_step_;
  float angle_step_;
  float max_distance_;
  int distance_bins_;
  int angle_bins_;
  int alpha_bins_;
  float alpha_bins_per_radian_;
  int64_t key_count_;
  std::vector<float> border_cosines_;  // cos(k * angle_step) for k = 1 .. angle bins - 1, falling
  static constexpr float kTwoPi = 6.28318530717958647692f;
};

// The local frame of a reference point: T maps p_ref to the origin and n_ref onto +x (section
// II-B: T_m for model points, T_s for scene points).
Eigen::Isometry3f referenceFrame(const Eigen::Vector3f& p_ref, const Eigen::Vector3f& n_ref);

// Angle of a point about the x axis of a reference frame, measured in the y-z plane from +y.
// alpha = planarAngle(T_s s_j) - planarAngle(T_m m_j) rotates the model pair onto the scene pair.
inline float planarAngle(const Eigen::Vector3f& p_in_reference_frame) {
  return std::atan2(p_in_reference_frame.z(), p_in_reference_frame.y());
}

// Pose from a local coordinate (eq. 2): T_scene_model = T_s^-1 * Rx(alpha) * T_m.
Eigen::Isometry3f poseFromLocalCoordinate(const Eigen::Isometry3f& T_s, const Eigen::Isometry3f& T_m, float alpha);

}  // namespace binpick::estimation
