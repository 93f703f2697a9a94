#pragma once
// The whole structured-light reconstruction: a capture (pattern images) and the rig's calibration
// in, an organized point cloud in the camera frame out, with why each pixel has no point.
//   decodeCapture (decoder.hpp) -> Triangulator (triangulation.hpp) -> filterCloud (cloud_filter.hpp)
// Thread-safety: a Reconstructor is immutable after construction; reconstruct() may be called
// from many threads at once.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "binpick/core/cancellation.hpp"
#include "binpick/io/capture.hpp"
#include "binpick/io/point_cloud.hpp"
#include "binpick/io/rig_calibration.hpp"
#include "binpick/reconstruction/cloud_filter.hpp"
#include "binpick/reconstruction/decoder.hpp"
#include "binpick/reconstruction/pixel_status.hpp"
#include "binpick/reconstruction/triangulation.hpp"

namespace binpick::reconstruction {

struct ReconstructionParams {
  DecodeParams decode;
  TriangulationParams triangulation;
  CloudFilterParams filter;
  // Sets the thread count of every stage (0: all cores).
  void setThreads(int threads);
  void validate() const;  // throws core::Error naming the stage and field
};

struct ReconstructionTimings {  // milliseconds
  double decode = 0.0;
  double triangulate = 0.0;
  double filter = 0.0;
  double total = 0.0;
};

struct Reconstruction {
  // Organized (camera width x height), camera frame, metres, NaN where there is no point; the
  // intensities are the white image on the sensor's scale [0, 1], for every pixel.
  io::PointCloud cloud;
  cv::Mat status;  // CV_8UC1 PixelStatus per pixel
  StatusCounts counts;
  ReconstructionTimings timings;
  CalibrationFit calibration_fit;  // from triangulation: measured on a sample of the pixels
  // Of the points, those read along their stripes (dark pixels, DecodeParams::stripe_reach): each
  // within half its run of codes of the truth rather than half a code.
  std::size_t points_along_stripes = 0;
  // What the caller should know about a capture that was reconstructed all the same (also logged
  // as warnings by the "reconstruction" logger), e.g. a geometry that triangulates poorly.
  std::vector<std::string> warnings;
  std::size_t validPoints() const { return counts[0]; }
};

class Reconstructor {
 public:
  // Precomputes what depends on the calibration. Throws core::Error on an invalid rig or
  // params.
  Reconstructor(const io::RigCalibration& rig, const ReconstructionParams& params = {});

  // Throws core::Error when the capture cannot be decoded (decoder.hpp), its images are not
  // the size of the calibration's camera, or its pattern set is not for a projector of the
  // calibration's projector size; core::Cancelled when `cancel` is set before a stage
  // (decoding, triangulation, filtering) begins.
  Reconstruction reconstruct(const io::Capture& capture, const core::CancelFlag* cancel = nullptr) const;

  const ReconstructionParams& params() const { return params_; }
  const io::RigCalibration& rig() const { return triangulator_.rig(); }

 private:
  ReconstructionParams params_;
  Triangulator triangulator_;
};

}  // namespace binpick::reconstruction
