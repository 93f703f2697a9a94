#pragma once
// Triangulation: from decoded projector coordinates to 3D points in the camera frame, with the
// lens distortion of both devices handled exactly.
//
// Each camera pixel's ray (undistorted once per calibration) is intersected with the light of
// the projector column it saw: the points of the ray that the projector maps onto that column.
// When rows were decoded too, the point minimises the distance in the projector image between
// its projection and the decoded (column, row) along the ray (ray-ray), and a row that lies
// farther than max_epipolar_error from the epipolar curve of the pixel marks it Inconsistent.
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
  // Projector pixels: how far a decoded row may lie from where the column's point projects.
  double max_epipolar_error = 1.5;
  int threads = 0;  // 0: all cores
  void validate() const;  // throws binpick::Error naming the field
};

struct TriangulatedCloud {
  // Organized (camera width x height), camera frame, metres; NaN where status is not Valid.
  PointCloud cloud;
  cv::Mat status;  // CV_8UC1 PixelStatus: the decoder's, plus Inconsistent / NoIntersection
};

class Triangulator {
 public:
  // Precomputes what depends only on the calibration (the camera ray of every pixel, the
  // projector's undistortion). Throws binpick::Error on an invalid rig or params.
  Triangulator(const RigCalibration& rig, const TriangulationParams& params = {});
  ~Triangulator();
  Triangulator(Triangulator&&) noexcept;
  Triangulator& operator=(Triangulator&&) noexcept;

  // Throws binpick::Error when `decoded` is not the camera's image size.
  TriangulatedCloud triangulate(const DecodedCapture& decoded) const;

  const RigCalibration& rig() const;

 private:
  struct Tables;
  RigCalibration rig_;
  TriangulationParams params_;
  std::unique_ptr<const Tables> tables_;
};

}  // namespace binpick::reconstruction
