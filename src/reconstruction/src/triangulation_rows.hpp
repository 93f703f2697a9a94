#pragma once
// Triangulation of one camera image row, in a few passes over small buffers: scalar passes for
// the table loads, and branch-free arithmetic passes the compiler vectorises.
// A pixel's result depends only on its own inputs (and never on its neighbours or on which
// thread runs the image row).
#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "binpick/io/rig_calibration.hpp"
#include "triangulation_tables.hpp"

namespace binpick::reconstruction::detail {

// The rig in single precision, as the per-pixel arithmetic uses it.
struct RigGeometry {
  float r[9] = {};             // R_projector_camera, row-major
  float c[3] = {};             // the camera centre in the projector frame
  float aspect_sq = 1.0f;      // (fx / fy)^2 of the projector
  float fx = 1.0f, fy = 1.0f;  // the projector's focal lengths, pixels
  float max_error_sq = 0.0f;   // (max_epipolar_error / fx)^2: normalised units
  // The epipolar label of the camera ray (a, b, 1) is (q3 . (a, b, 1)) / (q2 . (a, b, 1)):
  // n . e = (C x d) . e = d . (e x C), with d = R (a, b, 1).
  float q2[3] = {}, q3[3] = {};
  float max_depth = 0.0f;                // camera z beyond which rays count as parallel, metres
  bool column_when_inconsistent = true;  // TriangulationParams::column_when_row_inconsistent
};
RigGeometry makeRigGeometry(const io::RigCalibration& rig, const EpipolarPencil& pencil, double max_epipolar_error);

struct TriangulationImageRowInput {
  int width = 0;
  const float* ray_x = nullptr;  // CameraRays of this image row
  const float* ray_y = nullptr;
  const float* column = nullptr;  // decoded projector coordinates
  const float* row = nullptr;     // projector rows; nullptr: column-only capture
  // The calibration's residual field at each pixel (epipolar_residual.hpp), projector pixels:
  // the epipolar offset a pixel is judged from. Projector rows only.
  const float* expected_offset = nullptr;
  // Per pixel, the square of how many times max_epipolar_error it may lie from that offset:
  // 1, more for a pixel read along its stripe (DecodedCapture::stripe_run). Projector rows only.
  const float* limit_scale_sq = nullptr;
  const uint8_t* status = nullptr;
};

struct TriangulationImageRowOutput {
  Eigen::Vector3f* points = nullptr;
  uint8_t* status = nullptr;
  float* depth_per_px = nullptr;  // TriangulatedCloud::depth_per_projector_px
};

// Per-thread scratch, one float (or code) per pixel of an image row.
struct TriangulationScratch {
  explicit TriangulationScratch(int width);
  std::vector<float> label, fx, fy, px, py, pz, depth_per_px;
  std::vector<float> light;  // 2 or 4 interleaved floats per pixel
  std::vector<int32_t> code, cell;
  // Column-only solutions of the pixels whose projector row did not decode, in a capture with
  // projector rows.
  std::vector<float> column_px, column_py, column_pz, column_depth_per_px;
  std::vector<int32_t> column_code;
};

// Projector rows decoded; pixels whose projector row is NaN (the column decoded alone) are
// solved as column-only.
void triangulateImageRowWithProjectorRows(const RigGeometry& rig, const ProjectorTables& tables,
                                          const TriangulationImageRowInput& in, TriangulationScratch& scratch,
                                          const TriangulationImageRowOutput& out);
void triangulateImageRowColumnOnly(const RigGeometry& rig, const ProjectorTables& tables,
                                   const TriangulationImageRowInput& in, TriangulationScratch& scratch,
                                   const TriangulationImageRowOutput& out);

}  // namespace binpick::reconstruction::detail
