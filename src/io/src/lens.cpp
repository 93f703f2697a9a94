// LensIntrinsics: OpenCV's distortion model and its Newton inverse.
#include "binpick/io/lens.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "binpick/core/error.hpp"

namespace binpick::io {
namespace {

void require(bool ok, const std::string& what, const char* field, const char* rule, double value) {
  core::requireField(ok, what, field, rule, value);
}

constexpr int kMaxImageSide = 65536;

// Distorted normalised coordinates and their Jacobian with respect to the undistorted ones.
struct DistortionStep {
  Eigen::Vector2d value;
  Eigen::Matrix2d jacobian;
};

DistortionStep distortWithJacobian(const std::array<double, 5>& d, const Eigen::Vector2d& p) {
  const double k1 = d[0], k2 = d[1], p1 = d[2], p2 = d[3], k3 = d[4];
  const double x = p.x(), y = p.y();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
  const double dradial_dr2 = k1 + r2 * (2.0 * k2 + 3.0 * r2 * k3);
  DistortionStep step;
  step.value.x() = x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x);
  step.value.y() = y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y;
  // d(r2)/dx = 2x, d(r2)/dy = 2y.
  step.jacobian(0, 0) = radial + x * dradial_dr2 * 2.0 * x + 2.0 * p1 * y + 6.0 * p2 * x;
  step.jacobian(0, 1) = x * dradial_dr2 * 2.0 * y + 2.0 * p1 * x + 2.0 * p2 * y;
  step.jacobian(1, 0) = y * dradial_dr2 * 2.0 * x + 2.0 * p1 * x + 2.0 * p2 * y;
  step.jacobian(1, 1) = radial + y * dradial_dr2 * 2.0 * y + 6.0 * p1 * y + 2.0 * p2 * x;
  return step;
}

}  // namespace

void LensIntrinsics::validate(const std::string& what) const {
  require(width > 0 && width <= kMaxImageSide, what, "width", "in [1, 65536]", width);
  require(height > 0 && height <= kMaxImageSide, what, "height", "in [1, 65536]", height);
  require(std::isfinite(fx) && fx > 0.0, what, "fx", "positive", fx);
  require(std::isfinite(fy) && fy > 0.0, what, "fy", "positive", fy);
  require(std::isfinite(cx), what, "cx", "finite", cx);
  require(std::isfinite(cy), what, "cy", "finite", cy);
  for (double k : distortion) require(std::isfinite(k), what, "distortion", "finite", k);
}

bool LensIntrinsics::hasDistortion() const {
  for (double k : distortion) {
    if (k != 0.0) return true;
  }
  return false;
}

LensIntrinsics LensIntrinsics::scaled(double factor) const {
  if (!std::isfinite(factor) || factor <= 0.0) {
    throw core::Error("LensIntrinsics::scaled: factor must be positive (got " + std::to_string(factor) + ")");
  }
  LensIntrinsics lens = *this;
  lens.width = std::max(1, static_cast<int>(std::lround(width * factor)));
  lens.height = std::max(1, static_cast<int>(std::lround(height * factor)));
  lens.fx = fx * factor;
  lens.fy = fy * factor;
  // Pixel centres sit at integers: the image's left edge (-0.5) must stay the left edge.
  lens.cx = (cx + 0.5) * factor - 0.5;
  lens.cy = (cy + 0.5) * factor - 0.5;
  return lens;
}

Eigen::Vector2d LensIntrinsics::distort(const Eigen::Vector2d& normalised) const {
  return distortWithJacobian(distortion, normalised).value;
}

Eigen::Vector2d LensIntrinsics::undistort(const Eigen::Vector2d& normalised_distorted) const {
  if (!hasDistortion()) return normalised_distorted;
  // Newton on distort(p) = target, from the target itself: distortion is a small perturbation of
  // the identity inside the image, so a handful of steps reach machine precision.
  Eigen::Vector2d p = normalised_distorted;
  for (int iteration = 0; iteration < 20; ++iteration) {
    const DistortionStep step = distortWithJacobian(distortion, p);
    const Eigen::Vector2d residual = step.value - normalised_distorted;
    if (residual.squaredNorm() < 1e-30) return p;
    p -= step.jacobian.inverse() * residual;
  }
  // Where the model folds over (far outside a real lens's image) there is no unique inverse:
  // NaN rather than a confidently wrong ray.
  if ((distort(p) - normalised_distorted).norm() > 1e-9 || !p.allFinite()) {
    return Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  }
  return p;
}

Eigen::Vector2d LensIntrinsics::project(const Eigen::Vector3d& point) const {
  const Eigen::Vector2d d = distort(point.head<2>() / point.z());
  return {fx * d.x() + cx, fy * d.y() + cy};
}

Eigen::Vector3d LensIntrinsics::rayThroughPixel(const Eigen::Vector2d& pixel) const {
  const Eigen::Vector2d distorted((pixel.x() - cx) / fx, (pixel.y() - cy) / fy);
  const Eigen::Vector2d p = undistort(distorted);
  return Eigen::Vector3d(p.x(), p.y(), 1.0).normalized();
}

}  // namespace binpick::io
