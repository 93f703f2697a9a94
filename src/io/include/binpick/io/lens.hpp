#pragma once
// The pinhole + radial-tangential lens model of OpenCV (k1, k2, p1, p2, k3), for the camera and,
// as an inverse camera, for the projector. Pixel centres are at integer coordinates, (0, 0) being
// the centre of the top-left pixel; x right, y down, z forward. Value type: thread-safe.
#include <Eigen/Core>
#include <array>
#include <string>

namespace binpick::io {

struct LensIntrinsics {
  int width = 0;                       // pixels
  int height = 0;                      // pixels
  double fx = 0.0, fy = 0.0;           // focal lengths, pixels
  double cx = 0.0, cy = 0.0;           // principal point, pixels
  std::array<double, 5> distortion{};  // k1, k2, p1, p2, k3 (OpenCV's order)

  // Throws core::Error naming `what` (e.g. "camera") and the bad field.
  void validate(const std::string& what) const;

  // Where a point of the device frame (z > 0) lands on the image, lens distortion included.
  Eigen::Vector2d project(const Eigen::Vector3d& point) const;
  // Normalised image coordinates (x/z, y/z) with distortion applied / removed. `undistort`
  // inverts `distort` to well below 1e-6 pixel inside the image (Newton iterations), and gives
  // NaN where the model has no unique inverse (far outside the image of a real lens).
  Eigen::Vector2d distort(const Eigen::Vector2d& normalised) const;
  Eigen::Vector2d undistort(const Eigen::Vector2d& normalised_distorted) const;
  // Unit direction of the ray through a pixel (the inverse of `project`).
  Eigen::Vector3d rayThroughPixel(const Eigen::Vector2d& pixel) const;

  bool hasDistortion() const;
  // The same lens on a sensor binned by `factor` (0.5: half the pixels each way), keeping the
  // field of view: for fast tests and previews. Distortion is in normalised coordinates: unchanged.
  LensIntrinsics scaled(double factor) const;
};

}  // namespace binpick::io
