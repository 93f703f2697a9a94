#pragma once
// How a calibration fits a capture, measured on a sample of its decoded pixels: the public
// measureCalibrationFit (calibration_fit.hpp), and the residual field the Triangulator judges
// each pixel's epipolar error from (triangulation.hpp).
#include <Eigen/Geometry>
#include <vector>

#include "binpick/io/rig_calibration.hpp"
#include "binpick/reconstruction/decoder.hpp"
#include "binpick/reconstruction/triangulation.hpp"
#include "lookup_grid.hpp"
#include "triangulation_tables.hpp"

namespace binpick::reconstruction::detail {

// The smooth epipolar offset of a calibration that does not quite fit the rig: the median signed
// offset (projector pixels) of the decoded pixels over square tiles of the camera image.
struct EpipolarResidualField {
  int tile = 0;  // camera pixels
  int tiles_x = 0;
  int tiles_y = 0;
  std::vector<float> offset_px;  // per tile, row-major; empty: nothing measured (all zero)
  // The field at every pixel of camera row y (width pixels), bilinear between tile centres.
  void rowOffsets(int y, int width, float* out) const;
};

struct FitSampling {
  int stride = 1;                // every stride-th pixel of every stride-th row
  double limit_px = 1.5;         // TriangulationParams::max_epipolar_error
  double max_residual_px = 0.0;  // TriangulationParams::max_calibration_residual (0: no field)
  int threads = 1;
};

struct FitMeasurement {
  CalibrationFit fit;
  EpipolarResidualField field;
};

// The rig in double precision, as the per-pixel measures use it.
struct RigFrames {
  Eigen::Matrix3d r;  // camera -> projector rotation
  Eigen::Vector3d c;  // the camera centre in the projector frame
  double projector_fx = 1.0, projector_fy = 1.0;
};
RigFrames rigFrames(const io::RigCalibration& rig);

// `decoded` must have rows and be the camera's size (checked by the callers).
FitMeasurement measureFit(const RigFrames& rig, const CameraRays& rays, const LookupGrid<2>& undistort,
                          const DecodedCapture& decoded, const FitSampling& sampling);

}  // namespace binpick::reconstruction::detail
