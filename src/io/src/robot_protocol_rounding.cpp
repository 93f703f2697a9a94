// Fixed-point quaternions that point as close as their resolution allows.
#include <cmath>

#include "robot_codec.hpp"

namespace binpick::robot::detail {

namespace {

// The angle between the rotations of unit q and of nonzero p, up to a monotonic function: the
// part of p across q relative to the part along it.
double misalignment(const Eigen::Vector4d& p, const Eigen::Vector4d& q) {
  const double along = p.dot(q);
  return (p - along * q).squaredNorm() / (along * along);
}

}  // namespace

std::array<double, 4> roundQuaternion(const std::vector<double>& q, double unitsPerValue) {
  const Eigen::Vector4d unit(q[0], q[1], q[2], q[3]);
  const Eigen::Vector4d scaled = unit * unitsPerValue;
  Eigen::Vector4d floor;
  for (int k = 0; k < 4; ++k) floor[k] = std::floor(scaled[k]);
  Eigen::Vector4d best = scaled.array().round();
  double bestMisalignment = misalignment(best, unit);
  for (int corner = 0; corner < 16; ++corner) {
    Eigen::Vector4d candidate = floor;
    for (int k = 0; k < 4; ++k) candidate[k] += (corner >> k) & 1;
    const double candidateMisalignment = misalignment(candidate, unit);
    if (candidateMisalignment < bestMisalignment) {
      best = candidate;
      bestMisalignment = candidateMisalignment;
    }
  }
  return {best[0], best[1], best[2], best[3]};
}

}  // namespace binpick::robot::detail
