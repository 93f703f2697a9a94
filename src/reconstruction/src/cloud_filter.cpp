// filterCloud: depth range, crop box, noise, depth-edge and speckle removal on an organized cloud.
#include "binpick/reconstruction/cloud_filter.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "binpick/core/error.hpp"
#include "binpick/core/thread_count.hpp"
#include "binpick/reconstruction/pixel_status.hpp"
#include "depth_edges.hpp"
#include "edge_coverage.hpp"
#include "speckle.hpp"
#include "surface_median.hpp"

namespace binpick::reconstruction {
namespace {

void require(bool ok, const char* field, const char* rule, double value) {
  core::requireField(ok, "CloudFilterParams", field, rule, value);
}

bool hasNaN(const Eigen::Vector3d& v) { return v.array().isNaN().any(); }

void requireOptionalImage(const cv::Mat& image, const io::PointCloud& cloud, const char* what) {
  if (image.empty() || (image.type() == CV_32FC1 && image.cols == cloud.width && image.rows == cloud.height)) return;
  throw core::Error(std::string("filterCloud: the ") + what + " image must be empty or CV_32FC1 of the cloud's size " +
                    std::to_string(cloud.width) + "x" + std::to_string(cloud.height) + " (got " +
                    std::to_string(image.cols) + "x" + std::to_string(image.rows) + " of type " +
                    std::to_string(image.type()) + ")");
}

void checkInputs(const io::PointCloud& cloud, const cv::Mat& status, const PointPrecision& precision) {
  requireOptionalImage(precision.column_noise, cloud, "column noise");
  requireOptionalImage(precision.code_depth, cloud, "code depth");
  if (!cloud.isOrganized()) {
    throw core::Error("filterCloud: the cloud must be organized (got " + std::to_string(cloud.width) + "x" +
                      std::to_string(cloud.height) + " for " + std::to_string(cloud.size()) + " points)");
  }
  if (status.type() != CV_8UC1 || status.cols != cloud.width || status.rows != cloud.height) {
    throw core::Error("filterCloud: the status image must be CV_8UC1 of the cloud's size " +
                      std::to_string(cloud.width) + "x" + std::to_string(cloud.height) + " (got " +
                      std::to_string(status.cols) + "x" + std::to_string(status.rows) + " of type " +
                      std::to_string(status.type()) + ")");
  }
}

void removePoint(io::PointCloud& cloud, std::size_t i, uint8_t& status, PixelStatus reason) {
  cloud.points[i] = Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN());
  status = static_cast<uint8_t>(reason);
}

void removeFlagged(io::PointCloud& cloud, cv::Mat& status, const std::vector<uint8_t>& flagged, PixelStatus reason) {
  for (int y = 0; y < cloud.height; ++y) {
    uint8_t* row_status = status.ptr<uint8_t>(y);
    for (int x = 0; x < cloud.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * cloud.width + x;
      if (flagged[i]) removePoint(cloud, i, row_status[x], reason);
    }
  }
}

void applyDepthAndCrop(io::PointCloud& cloud, cv::Mat& status, const CloudFilterParams& params) {
  const bool crop = !params.crop.isEmpty();
  const double min_depth = params.min_depth, max_depth = params.max_depth;
  for (int y = 0; y < cloud.height; ++y) {
    uint8_t* row_status = status.ptr<uint8_t>(y);
    for (int x = 0; x < cloud.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * cloud.width + x;
      const Eigen::Vector3f& p = cloud.points[i];
      // Missing points are NaN, which fails every comparison: they keep their status.
      if (p.z() < min_depth || p.z() > max_depth) {
        removePoint(cloud, i, row_status[x], PixelStatus::OutOfDepthRange);
      } else if (crop && p.allFinite() && !params.crop.contains(p.cast<double>())) {
        removePoint(cloud, i, row_status[x], PixelStatus::OutsideCrop);
      }
    }
  }
}

void applySurfaceMedian(io::PointCloud& cloud, cv::Mat& status, const CloudFilterParams& params,
                        const cv::Mat& column_noise) {
  const cv::Mat noise = column_noise.empty() || column_noise.isContinuous() ? column_noise : column_noise.clone();
  detail::MedianGate gate;
  gate.max_intensity = static_cast<float>(params.median_max_intensity);
  gate.noise = noise.empty() ? nullptr : noise.ptr<float>(0);
  gate.min_noise = static_cast<float>(params.median_min_noise);
  gate.lone_max_noise = static_cast<float>(params.median_lone_max_noise);
  removeFlagged(cloud, status,
                detail::smoothToSurfaceMedian(cloud, static_cast<float>(params.median_reach),
                                              static_cast<float>(params.median_max_pull), gate,
                                              core::resolveThreadCount(params.threads)),
                PixelStatus::DepthEdge);
}

// The smallest step each point's decoding allows (CloudFilterParams::min_step_in_codes), metres;
// empty without code depths.
std::vector<float> coarseSteps(const cv::Mat& code_depth, const CloudFilterParams& params) {
  if (code_depth.empty()) return {};
  std::vector<float> steps;
  steps.reserve(code_depth.total());
  const auto codes = static_cast<float>(params.min_step_in_codes);
  for (int y = 0; y < code_depth.rows; ++y) {
    const float* row = code_depth.ptr<float>(y);
    for (int x = 0; x < code_depth.cols; ++x) steps.push_back(codes * row[x]);
  }
  return steps;
}

const float* orNull(const std::vector<float>& values) { return values.empty() ? nullptr : values.data(); }

void applyDepthEdges(io::PointCloud& cloud, cv::Mat& status, const CloudFilterParams& params,
                     const std::vector<float>& coarse_steps) {
  removeFlagged(cloud, status,
                detail::findDepthEdgeOutliers(cloud, static_cast<float>(params.edge_max_jump),
                                              params.edge_min_neighbours, params.edge_min_support, orNull(coarse_steps),
                                              core::resolveThreadCount(params.threads)),
                PixelStatus::DepthEdge);
}

void applyEdgeCoverage(io::PointCloud& cloud, cv::Mat& status, const CloudFilterParams& params) {
  detail::EdgeCoverageTest test;
  test.reach = params.edge_side_reach;
  test.max_step = static_cast<float>(params.edge_max_jump);
  test.min_contrast = static_cast<float>(params.edge_side_min_contrast);
  removeFlagged(cloud, status,
                detail::findOtherSideEdgePixels(cloud, status, test, core::resolveThreadCount(params.threads)),
                PixelStatus::DepthEdge);
}

void applySpeckle(io::PointCloud& cloud, cv::Mat& status, const CloudFilterParams& params,
                  const std::vector<float>& coarse_steps) {
  const detail::DepthStep step{static_cast<float>(params.speckle_max_step), orNull(coarse_steps)};
  removeFlagged(cloud, status,
                detail::findSpeckles(cloud, step, params.speckle_min_pixels, core::resolveThreadCount(params.threads)),
                PixelStatus::Speckle);
}

}  // namespace

void CloudFilterParams::validate() const {
  require(std::isfinite(min_depth) && min_depth >= 0.0, "min_depth", "finite and >= 0", min_depth);
  require(!std::isnan(max_depth) && max_depth > min_depth, "max_depth", "above min_depth", max_depth);
  // A NaN corner would make the box non-empty yet contain nothing: every point would go.
  core::requireField(!hasNaN(crop.min()) && !hasNaN(crop.max()), "CloudFilterParams", "crop", "free of NaN",
                     "a NaN corner");
  require(std::isfinite(speckle_max_step) && speckle_max_step > 0.0, "speckle_max_step", "positive and finite",
          speckle_max_step);
  require(speckle_min_pixels >= 0, "speckle_min_pixels", ">= 0", speckle_min_pixels);
  require(std::isfinite(median_reach) && median_reach >= 0.0, "median_reach", "finite and >= 0", median_reach);
  require(std::isfinite(median_max_pull) && median_max_pull > 0.0, "median_max_pull", "positive and finite",
          median_max_pull);
  require(!std::isnan(median_max_intensity) && median_max_intensity >= 0.0, "median_max_intensity", ">= 0",
          median_max_intensity);
  require(!std::isnan(median_min_noise) && median_min_noise >= 0.0, "median_min_noise", ">= 0", median_min_noise);
  require(!std::isnan(median_lone_max_noise) && median_lone_max_noise >= 0.0, "median_lone_max_noise", ">= 0",
          median_lone_max_noise);
  require(std::isfinite(edge_max_jump) && edge_max_jump >= 0.0, "edge_max_jump", "finite and >= 0", edge_max_jump);
  require(edge_min_neighbours >= 1 && edge_min_neighbours <= 8, "edge_min_neighbours", "in [1, 8]",
          edge_min_neighbours);
  require(edge_min_support >= 1 && edge_min_support <= 8, "edge_min_support", "in [1, 8]", edge_min_support);
  require(edge_side_reach >= 0 && edge_side_reach <= 16, "edge_side_reach", "in [0, 16] pixels", edge_side_reach);
  require(std::isfinite(edge_side_min_contrast) && edge_side_min_contrast >= 0.0 && edge_side_min_contrast <= 1.0,
          "edge_side_min_contrast", "in [0, 1]", edge_side_min_contrast);
  require(std::isfinite(min_step_in_codes) && min_step_in_codes >= 0.0, "min_step_in_codes", "finite and >= 0",
          min_step_in_codes);
  require(threads >= 0, "threads", ">= 0", threads);
}

void filterCloud(io::PointCloud& cloud, cv::Mat& status, const CloudFilterParams& params,
                 const PointPrecision& precision) {
  params.validate();
  checkInputs(cloud, status, precision);
  // Triangulated points lie in front of the camera: the default range and no crop remove nothing.
  const CloudFilterParams defaults;
  const bool limits_depth = params.min_depth > defaults.min_depth || params.max_depth < defaults.max_depth;
  if (limits_depth || !params.crop.isEmpty()) applyDepthAndCrop(cloud, status, params);
  // Without the decoder's noise, which points are noisy is unknown: only median_min_noise = 0
  // (every dark point) smooths such a cloud.
  const bool noise_known = !precision.column_noise.empty() || params.median_min_noise == 0.0;
  if (params.median_reach > 0.0 && noise_known) applySurfaceMedian(cloud, status, params, precision.column_noise);
  const std::vector<float> coarse_steps = coarseSteps(precision.code_depth, params);
  if (params.edge_max_jump > 0.0) applyDepthEdges(cloud, status, params, coarse_steps);
  if (params.edge_max_jump > 0.0 && params.edge_side_reach > 0) applyEdgeCoverage(cloud, status, params);
  if (params.speckle_min_pixels > 1) applySpeckle(cloud, status, params, coarse_steps);
}

}  // namespace binpick::reconstruction
