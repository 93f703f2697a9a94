// The print averaged over each camera pixel's footprint on the board.
#include "board_albedo.hpp"

#include <cmath>

namespace binpick::simulation::detail {
namespace {

// Points closer than this to z = 0 are on the print (the other faces are at least the board's
// thickness away, or meet it only at its outline, where the print is white margin).
constexpr double kPrintTolerance = 1e-6;  // metres
// Step of the finite differences of the projection: small against a pixel's footprint (about
// half a millimetre), large against rounding.
constexpr double kJacobianStep = 1e-5;  // metres

// Board metres per camera pixel at `xy` on the print: columns are the board displacement of a
// one-pixel step in u and in v.
Eigen::Matrix2d pixelFootprint(const io::LensIntrinsics& camera, const Eigen::Isometry3d& T,
                               const Eigen::Vector2d& xy) {
  const Eigen::Vector3d p(xy.x(), xy.y(), 0.0);
  const Eigen::Vector2d pixel = camera.project(T * p);
  Eigen::Matrix2d jacobian;  // camera pixels per board metre
  jacobian.col(0) = (camera.project(T * (p + Eigen::Vector3d(kJacobianStep, 0, 0))) - pixel) / kJacobianStep;
  jacobian.col(1) = (camera.project(T * (p + Eigen::Vector3d(0, kJacobianStep, 0))) - pixel) / kJacobianStep;
  return jacobian.inverse();
}

}  // namespace

AlbedoFunction boardPixelAlbedo(const CalibrationBoard& board, const io::LensIntrinsics& camera,
                                const Eigen::Isometry3d& T_camera_board, int32_t board_id, int samples,
                                float other_albedo) {
  const auto white = static_cast<float>(board.spec().white_albedo);
  return [&board, &camera, T_camera_board, board_id, samples, other_albedo, white](
             int32_t object_id, const Eigen::Vector3f& object_point) {
    if (object_id != board_id) return other_albedo;
    if (std::abs(object_point.z()) > kPrintTolerance) return white;
    const Eigen::Vector2d xy = object_point.head<2>().cast<double>();
    const Eigen::Matrix2d footprint = pixelFootprint(camera, T_camera_board, xy);
    if (!footprint.allFinite()) return board.albedo(xy);  // seen edge-on: no area to average
    return board.meanAlbedo(xy, footprint, samples);
  };
}

}  // namespace binpick::simulation::detail
