#include "rig_depth_error.hpp"

#include <algorithm>
#include <cmath>

#include "binpick/reconstruction/pixel_status.hpp"
#include "binpick/reconstruction/triangulation.hpp"

namespace binpick::test {
namespace {

// The true rig's decoding of a plane at camera z = `distance`: NaN where the projector does not
// light the pixel.
reconstruction::DecodedCapture decodedPlane(const io::RigCalibration& truth, double distance) {
  reconstruction::DecodedCapture decoded;
  decoded.width = truth.camera.width;
  decoded.height = truth.camera.height;
  decoded.column = cv::Mat(decoded.height, decoded.width, CV_32FC1, cv::Scalar(NAN));
  decoded.row = cv::Mat(decoded.height, decoded.width, CV_32FC1, cv::Scalar(NAN));
  decoded.status =
      cv::Mat(decoded.height, decoded.width, CV_8UC1, cv::Scalar(static_cast<int>(reconstruction::PixelStatus::Unlit)));
  for (int y = 0; y < decoded.height; ++y) {
    for (int x = 0; x < decoded.width; ++x) {
      const Eigen::Vector3d ray = truth.camera.rayThroughPixel({x, y});
      const Eigen::Vector3d point = truth.T_projector_camera * (ray * (distance / ray.z()));
      if (point.z() <= 0.0) continue;
      const Eigen::Vector2d pixel = truth.projector.project(point);
      if (pixel.x() < 0 || pixel.y() < 0 || pixel.x() > truth.projector.width - 1 ||
          pixel.y() > truth.projector.height - 1) {
        continue;
      }
      decoded.column.at<float>(y, x) = static_cast<float>(pixel.x());
      decoded.row.at<float>(y, x) = static_cast<float>(pixel.y());
      decoded.status.at<uint8_t>(y, x) = static_cast<uint8_t>(reconstruction::PixelStatus::Valid);
    }
  }
  return decoded;
}

}  // namespace

double medianDepthErrorMm(const io::RigCalibration& recovered, const io::RigCalibration& truth,
                          const std::vector<double>& distances, int step) {
  const reconstruction::Triangulator triangulator(recovered);
  std::vector<double> errors;
  for (const double distance : distances) {
    const reconstruction::TriangulatedCloud cloud = triangulator.triangulate(decodedPlane(truth, distance));
    for (int y = 0; y < cloud.cloud.height; y += step) {
      for (int x = 0; x < cloud.cloud.width; x += step) {
        const Eigen::Vector3f& p = cloud.cloud.points[static_cast<std::size_t>(y) * cloud.cloud.width + x];
        if (std::isfinite(p.z())) errors.push_back(1e3 * std::abs(p.z() - distance));
      }
    }
  }
  if (errors.empty()) return NAN;
  const auto middle = errors.begin() + static_cast<std::ptrdiff_t>(errors.size() / 2);
  std::nth_element(errors.begin(), middle, errors.end());
  return *middle;
}

}  // namespace binpick::test
