#pragma once
// What triangulation needs of the two lenses and their placement, precomputed once per
// calibration so that the per-pixel work is a table load and a little arithmetic.
#include <Eigen/Geometry>
#include <vector>

#include "binpick/io/lens.hpp"
#include "lookup_grid.hpp"

namespace binpick::reconstruction::detail {

// Every camera pixel's ray as undistorted normalised coordinates: the ray is (x, y, 1), so a
// point on it at ray parameter t has camera z = t. Row-major, one array per coordinate (the
// triangulation loops read them as contiguous streams).
struct CameraRays {
  int width = 0;
  int height = 0;
  std::vector<float> x;
  std::vector<float> y;
};

// The epipolar planes: every plane through both optical centres, in the projector frame. They
// form a pencil about the baseline C (the camera centre), labelled by
//   l = (n . e3) / (n . e2),   n = C x w
// for a plane through the projector ray w: e2 is the normal of the plane through the
// projector's optical axis, e3 = C/|C| x e2, so l = tan of the plane's tilt from that one (0 at
// the principal point, about the normalised row for a horizontal baseline). A camera ray
// C + t d lies in the plane of l((C x d)); `valid` is false when the baseline lies along the
// projector's axis (then the planes fan out through the image and columns carry no depth).
struct EpipolarPencil {
  Eigen::Vector3d e2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d e3 = Eigen::Vector3d::Zero();
  bool valid = false;
};
EpipolarPencil makeEpipolarPencil(const Eigen::Vector3d& camera_centre_in_projector);

struct ProjectorTables {
  // Distorted projector pixel (x, y) -> undistorted normalised (u, v).
  LookupGrid<2> undistort;
  // (distorted column x, epipolar label l) -> (u, v, distorted row y, unused): where the light of
  // the column crosses the epipolar plane, i.e. the one projector ray of that column a camera
  // ray in that plane can meet. Curved columns (distortion) are handled exactly this way, with
  // no iteration per pixel. Empty when the pencil is not valid.
  LookupGrid<4> epipolar;
  // Decoded coordinates accepted (the image plus the tables' margin), pixels.
  float min_column = 0.0f, max_column = 0.0f;
  float min_row = 0.0f, max_row = 0.0f;
};

CameraRays buildCameraRays(const io::LensIntrinsics& camera, int threads);
// ProjectorTables::undistort alone, for readers of decoded coordinates that need no epipolar
// table (calibration_fit.hpp).
LookupGrid<2> buildUndistortGrid(const io::LensIntrinsics& lens, int threads);
ProjectorTables buildProjectorTables(const io::LensIntrinsics& projector, const EpipolarPencil& pencil,
                                     const Eigen::Vector3d& camera_centre_in_projector, int threads);

}  // namespace binpick::reconstruction::detail
