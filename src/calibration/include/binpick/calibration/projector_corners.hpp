#pragma once
// Where the projector sees each board corner that the camera found, after Moreno & Taubin
// ("Simple, Accurate, and Robust Projector-Camera Calibration", 3DIMPVT 2012): the decoded
// pixels around the corner (camera pixel -> projector column and row) are fitted with a local
// homography, robustly (cv::findHomography, RANSAC), and the homography is evaluated at the
// corner's sub-pixel camera position. The board is planar and the window small, so a homography
// models the camera-to-projector map there, lens distortion included, to well below the decoding
// noise; the fit averages that noise over hundreds of pixels. Black squares and marker bits may
// decode poorly or not at all: the fit only needs decoded pixels on enough of the window.
// Pixel centres at integer coordinates in both images. Stateless: thread-safe (uses OpenMP threads).
#include <Eigen/Core>
#include <vector>

#include "binpick/calibration/board_detection.hpp"
#include "binpick/reconstruction/decoder.hpp"

namespace binpick::calibration {

struct ProjectorCornerParams {
  // Camera pixels either side of the corner whose decoded pixels are fitted: about a square's
  // side in pixels (larger windows average more noise but bend with the lens distortion).
  int half_window = 40;
  // A corner with fewer decoded pixels (valid column and row) in its window is dropped.
  int min_decoded_pixels = 100;
  // RANSAC inlier threshold, projector pixels, and the share of the decoded pixels that must be
  // inliers of the homography. Gray codes without phase decode to half a projector pixel; on the
  // virtual cell a 1-pixel threshold rejected honest pixels and doubled the worst corner's error.
  double ransac_threshold = 2.0;
  double min_inlier_share = 0.5;
  // The corner must lie this far (camera pixels) inside the convex hull of the inliers: a
  // homography extrapolated beyond its data, e.g. where the board leaves the projector's light,
  // is not trusted.
  double min_hull_depth = 2.0;
  int threads = 0;        // corners fitted in parallel; 0: all cores
  void validate() const;  // throws core::Error naming the field
};

struct ProjectorCorner {
  int id = 0;                 // the board corner (BoardLayout::cornerPoint)
  Eigen::Vector2d camera;     // its camera pixel (from the detection)
  Eigen::Vector2d projector;  // its projector pixel
  int decoded = 0;            // decoded pixels in the window
  int inliers = 0;            // of those, inliers of the homography
};

struct ProjectorCorners {
  std::vector<ProjectorCorner> corners;  // the corners kept, in the detection's order
  // Corners dropped, by reason.
  int too_few_decoded = 0;  // fewer than min_decoded_pixels in the window
  int poor_fit = 0;         // no homography, or too few inliers
  int outside_data = 0;     // the corner lies outside (or at the edge of) the fitted pixels
  int dropped() const { return too_few_decoded + poor_fit + outside_data; }
};

// One projector pixel per corner of `detection` that passes the checks above (`detection` and
// `decoded` come from the same capture). Throws core::Error when `decoded` lacks columns or
// rows (a capture without column or row codes) or the params are bad.
ProjectorCorners findProjectorCorners(const reconstruction::DecodedCapture& decoded, const BoardDetection& detection,
                                      const ProjectorCornerParams& params = {});

}  // namespace binpick::calibration
