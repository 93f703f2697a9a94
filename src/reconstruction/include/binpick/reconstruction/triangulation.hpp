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
// The calibration's own residual: a calibration that does not quite fit the rig (a real one,
// fitted to a few board poses) puts every decoded pixel off its epipolar line by an offset that
// varies smoothly across the image, 1 to 15 projector pixels far from where the board was, while
// a misdecoded pixel lies off its neighbours' offset. That smooth field is measured on each
// capture (the median offset over tiles of 32 x 32 camera pixels, every 4th pixel sampled) and a
// pixel is judged by its distance from it; the field's largest value is reported
// (CalibrationFit), so that a calibration worth redoing is still named.
//
// Statuses: only Valid input pixels are triangulated; the others keep the decoder's status and a
// NaN point. Coordinates (or NaN) outside the projector image widened by a margin of 8 pixels
// give CodeOutOfRange; rays that meet the light behind the camera or the projector, that are
// within 0.06 degrees of parallel to it (points beyond 1000 baselines), or whose column's light
// crosses their epipolar plane only outside the projector image give NoIntersection.
//
// Thread-safety: a Triangulator is immutable after construction; triangulate() may be called
// from many threads at once.
#include <cstddef>
#include <limits>
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
  // Projector pixels: the largest epipolar offset of the calibration's residual field that
  // max_epipolar_error is measured from; larger offsets are clipped to it, so a calibration of
  // another rig (or codes at another scale) still leaves its pixels Inconsistent. 0: every pixel
  // is judged from its epipolar line itself.
  double max_calibration_residual = 20.0;
  int threads = 0;        // 0: all cores
  void validate() const;  // throws core::Error naming the field
};

// Whether a calibration fits a capture (calibration_fit.hpp): how far each decoded pixel's
// projector ray misses its camera ray, over the pixels that decoded a column and a row.
struct CalibrationFit {
  std::size_t pixels = 0;           // decoded pixels with a column and a row inside the projector image
  std::size_t pixels_with_gap = 0;  // of those, whose rays pass closest in front of both devices
  double median_gap_mm = std::numeric_limits<double>::quiet_NaN();
  double median_epipolar_px = std::numeric_limits<double>::quiet_NaN();
  // The calibration's residual field (TriangulationParams::max_calibration_residual): its largest
  // offset before clipping over 95% of the image (a region decoded all wrong would name hundreds
  // of pixels), and the median distance of the pixels from it. NaN when not measured.
  double largest_residual_px = std::numeric_limits<double>::quiet_NaN();
  double median_off_residual_px = std::numeric_limits<double>::quiet_NaN();
  double epipolar_limit_px = 0.0;  // TriangulationParams::max_epipolar_error
  double residual_limit_px = 0.0;  // TriangulationParams::max_calibration_residual
  // Of `pixels`, farther than the limit: from the residual field where it is followed, else from
  // the epipolar line itself.
  double beyond_limit_share = 0.0;
  // False for a capture without rows (nothing to check: a column alone always meets the ray) or
  // without a decoded pixel.
  bool measured() const { return pixels > 0; }
};

struct TriangulatedCloud {
  // Organized (camera width x height), camera frame, metres; NaN where status is not Valid.
  io::PointCloud cloud;
  cv::Mat status;  // CV_8UC1 PixelStatus: the decoder's, plus Inconsistent / NoIntersection
  // Camera z per projector pixel along the epipolar line (metres): the depth one decoded step
  // spans at that pixel is this times the step. CV_32FC1, NaN where status is not Valid.
  cv::Mat depth_per_projector_px;
  CalibrationFit calibration_fit;  // measured on a sample of the pixels; empty without rows
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
