// Projector corners: a local homography per board corner, fitted to the decoded pixels around it.
#include "binpick/calibration/projector_corners.hpp"

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "binpick/core/error.hpp"
#include "binpick/core/thread_count.hpp"

namespace binpick::calibration {
namespace {

// Camera pixels relative to the corner: the homography is then evaluated at the origin, and the
// coordinates stay small for the float arithmetic of OpenCV's point types.
struct WindowSamples {
  std::vector<cv::Point2f> camera;
  std::vector<cv::Point2f> projector;
};

WindowSamples decodedPixelsAround(const reconstruction::DecodedCapture& decoded, const Eigen::Vector2d& corner,
                                  int half_window) {
  const int cx = static_cast<int>(std::lround(corner.x()));
  const int cy = static_cast<int>(std::lround(corner.y()));
  const int x0 = std::max(0, cx - half_window), x1 = std::min(decoded.width - 1, cx + half_window);
  const int y0 = std::max(0, cy - half_window), y1 = std::min(decoded.height - 1, cy + half_window);
  WindowSamples samples;
  for (int y = y0; y <= y1; ++y) {
    const float* column = decoded.column.ptr<float>(y);
    const float* row = decoded.row.ptr<float>(y);
    for (int x = x0; x <= x1; ++x) {
      if (!std::isfinite(column[x]) || !std::isfinite(row[x])) continue;
      samples.camera.emplace_back(static_cast<float>(x - corner.x()), static_cast<float>(y - corner.y()));
      samples.projector.emplace_back(column[x], row[x]);
    }
  }
  return samples;
}

// How far the corner (the origin) lies inside the convex hull of the inliers; negative outside.
double hullDepth(const WindowSamples& samples, const std::vector<uchar>& inlier) {
  std::vector<cv::Point2f> points;
  for (std::size_t i = 0; i < inlier.size(); ++i) {
    if (inlier[i]) points.push_back(samples.camera[i]);
  }
  std::vector<cv::Point2f> hull;
  cv::convexHull(points, hull);
  return cv::pointPolygonTest(hull, cv::Point2f(0.0f, 0.0f), true);
}

// The homography's image of the origin, when it is finite.
std::optional<Eigen::Vector2d> mapOrigin(const cv::Mat& homography) {
  if (homography.empty()) return std::nullopt;
  const double w = homography.at<double>(2, 2);
  if (!(std::abs(w) > 1e-12)) return std::nullopt;
  const Eigen::Vector2d p(homography.at<double>(0, 2) / w, homography.at<double>(1, 2) / w);
  if (!p.allFinite()) return std::nullopt;
  return p;
}

enum class CornerOutcome { Kept, TooFewDecoded, PoorFit, OutsideData };

struct CornerFit {
  CornerOutcome outcome = CornerOutcome::TooFewDecoded;
  Eigen::Vector2d projector = Eigen::Vector2d::Zero();
  int decoded = 0;
  int inliers = 0;
};

CornerFit fitCorner(const reconstruction::DecodedCapture& decoded, const Eigen::Vector2d& corner,
                    const ProjectorCornerParams& params) {
  CornerFit fit;
  const WindowSamples samples = decodedPixelsAround(decoded, corner, params.half_window);
  fit.decoded = static_cast<int>(samples.camera.size());
  if (fit.decoded < params.min_decoded_pixels) return fit;
  std::vector<uchar> inlier;
  const cv::Mat homography =
      cv::findHomography(samples.camera, samples.projector, cv::RANSAC, params.ransac_threshold, inlier);
  const std::optional<Eigen::Vector2d> projector = mapOrigin(homography);
  fit.inliers = homography.empty() ? 0 : cv::countNonZero(inlier);
  fit.outcome = CornerOutcome::PoorFit;
  if (!projector || fit.inliers < params.min_inlier_share * fit.decoded) return fit;
  fit.outcome = CornerOutcome::OutsideData;
  if (hullDepth(samples, inlier) < params.min_hull_depth) return fit;
  fit.outcome = CornerOutcome::Kept;
  fit.projector = *projector;
  return fit;
}

}  // namespace

void ProjectorCornerParams::validate() const {
  const std::string owner = "ProjectorCornerParams";
  core::requireField(half_window >= 3 && half_window <= 500, owner, "half_window", "in [3, 500]", half_window);
  core::requireField(min_decoded_pixels >= 8, owner, "min_decoded_pixels", ">= 8", min_decoded_pixels);
  core::requireField(std::isfinite(ransac_threshold) && ransac_threshold > 0.0, owner, "ransac_threshold", "positive",
                     ransac_threshold);
  core::requireField(std::isfinite(min_inlier_share) && min_inlier_share > 0.0 && min_inlier_share <= 1.0, owner,
                     "min_inlier_share", "in (0, 1]", min_inlier_share);
  core::requireField(std::isfinite(min_hull_depth) && min_hull_depth >= 0.0, owner, "min_hull_depth", ">= 0",
                     min_hull_depth);
  core::requireField(threads >= 0, owner, "threads", ">= 0", threads);
}

ProjectorCorners findProjectorCorners(const reconstruction::DecodedCapture& decoded, const BoardDetection& detection,
                                      const ProjectorCornerParams& params) {
  params.validate();
  if (decoded.column.empty() || decoded.row.empty()) {
    throw core::Error(
        "projector corners need both the projector's columns and rows: capture with column and"
        " row codes (pattern_set.column_codes and row_codes)");
  }
  // One slot per corner, filled in parallel and read in order: the same result on any number
  // of threads.
  const int count = static_cast<int>(detection.ids.size());
  std::vector<CornerFit> fits(detection.ids.size());
#pragma omp parallel for num_threads(core::resolveThreadCount(params.threads)) schedule(dynamic, 1)
  for (int i = 0; i < count; ++i) {
    try {
      fits[i] = fitCorner(decoded, detection.pixels[i], params);
    } catch (const cv::Exception&) {
      // Degenerate samples. An exception must not leave the parallel loop: it would terminate.
      fits[i].outcome = CornerOutcome::PoorFit;
    }
  }
  ProjectorCorners result;
  for (int i = 0; i < count; ++i) {
    const CornerFit& fit = fits[i];
    result.too_few_decoded += fit.outcome == CornerOutcome::TooFewDecoded ? 1 : 0;
    result.poor_fit += fit.outcome == CornerOutcome::PoorFit ? 1 : 0;
    result.outside_data += fit.outcome == CornerOutcome::OutsideData ? 1 : 0;
    if (fit.outcome != CornerOutcome::Kept) continue;
    result.corners.push_back({detection.ids[i], detection.pixels[i], fit.projector, fit.decoded, fit.inliers});
  }
  return result;
}

}  // namespace binpick::calibration
