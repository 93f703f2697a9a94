#pragma once
// Triangulation: from decoded projector coordinates to 3D points in the camera frame, with the
// lens distortion of both devices handled exactly.
//
// Each camera pixel's ray (undistorted once per calibration) is intersected with the light of
// the projector column it saw: the points of the ray that the projector maps onto that column.
// Under distortion a column's light is a curved surface; it is met exactly where it crosses the
// ray's epipolar plane (tabulated once per calibration over column and plane: no iteration per
// pixel). When rows were decoded too, the point minimises the distance in the (undistorted)
// projector image between its projection and the decoded (column, row) along the ray (ray-ray),
// and a decoded pixel that lies farther than max_epipolar_error from the pixel's epipolar line
// marks it Inconsistent, or is solved from the column alone (column_when_row_inconsistent). A
// pixel whose row is NaN (the decoder kept its column alone) is solved from the column.
//
// Statuses: only Valid input pixels are triangulated; the others keep the decoder's status and a
// NaN point. Coordinates (or NaN) outside the projector image widened by a margin of 8 pixels
// give CodeOutOfRange; rays that meet the light behind the camera or the projector, that are
// within 0.06 degrees of parallel to it (points beyond 1000 baselines), or whose column's light
// crosses their epipolar plane only outside the projector image give NoIntersection.
//
// Thread-safety: a Triangulator is immutable after construction; triangulate() may be called
// from many threads at once.
#include <memory>
#include <opencv2/core.hpp>

#include "binpick/io/point_cloud.hpp"
#include "binpick/io/rig_calibration.hpp"
#include "binpick/reconstruction/decoder.hpp"

namespace binpick::reconstruction {

struct TriangulationParams {
  // Projector pixels: how far the decoded (column, row) may lie from the pixel's epipolar line,
  // measured in the undistorted projector image (distortion changes lengths there by a few per
  // cent at most for real lenses). Used only when rows were decoded.
  double max_epipolar_error = 1.5;
  // A pixel whose decoded row lies off its epipolar line (a wrong row) is triangulated from its
  // column alone, as a pixel whose row did not decode is; false: it is Inconsistent.
  bool column_when_row_inconsistent = false;
  int threads = 0;        // 0: all cores
  void validate() const;  // throws core::Error naming the field
};

struct TriangulatedCloud {
  // Organized (camera width x height), camera frame, metres; NaN where status is not Valid.
  io::PointCloud cloud;
  cv::Mat status;  // CV_8UC1 PixelStatus: the decoder's, plus Inconsistent / NoIntersection
};

class Triangulator {
 public:
  // Precomputes what depends only on the calibration (the camera ray of every pixel, the
  // projector's undistortion). Throws core::Error on an invalid rig or params.
  Triangulator(const io::RigCalibration& rig, const TriangulationParams& params = {});
  ~Triangulator();
  Triangulator(Triangulator&&) noexcept;
  Triangulator& operator=(Triangulator&&) noexcept;

  // Throws core::Error when `decoded` is not the camera's image size.
  TriangulatedCloud triangulate(const DecodedCapture& decoded) const;

  const io::RigCalibration& rig() const;

 private:
  struct Tables;
  io::RigCalibration rig_;
  TriangulationParams params_;
  std::unique_ptr<const Tables> tables_;
};

}  // namespace binpick::reconstruction
