// One device's own solve: chosen terms, restarts out of local minima, the per-term report.
#include "lens_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <string>

#include "binpick/core/error.hpp"

namespace binpick::calibration::detail {
namespace {

constexpr double kDegreesPerRadian = 180.0 / 3.14159265358979323846;

// OpenCV's flags holding the terms not in `terms` (at 0 from a fresh start, at the start's
// value with an intrinsic guess).
int heldTermFlags(const DistortionTerms& terms) {
  return (terms.k1 ? 0 : cv::CALIB_FIX_K1) | (terms.k2 ? 0 : cv::CALIB_FIX_K2) |
         (terms.tangential ? 0 : cv::CALIB_ZERO_TANGENT_DIST) | (terms.k3 ? 0 : cv::CALIB_FIX_K3);
}

std::vector<Eigen::Vector3d> boardNormals(const std::vector<cv::Mat>& rvecs) {
  std::vector<Eigen::Vector3d> normals;
  for (const cv::Mat& rvec : rvecs) {
    cv::Mat rotation;
    cv::Rodrigues(rvec, rotation);
    normals.emplace_back(rotation.at<double>(0, 2), rotation.at<double>(1, 2), rotation.at<double>(2, 2));
  }
  return normals;
}

// With an intrinsic guess the image size serves only OpenCV's check that the principal point
// lies inside the image. A projector's often does not (its lens is shifted: the principal point
// below the image), so the size is widened to hold the start's.
cv::Size sizeHolding(cv::Size size, const cv::Mat& matrix) {
  const auto holding = [](int side, double centre) {
    return std::isfinite(centre) ? std::max(side, static_cast<int>(std::ceil(std::abs(centre))) * 2 + 2) : side;
  };
  return {holding(size.width, matrix.at<double>(0, 2)), holding(size.height, matrix.at<double>(1, 2))};
}

// With a `start`, from its intrinsics (CALIB_USE_INTRINSIC_GUESS); a term the start holds and
// `terms` fits is freed from the start's value, 0.
LensFit calibrateLens(const LensData& data, const DistortionTerms& terms, const LensFit* start = nullptr) {
  LensFit fit;
  int flags = heldTermFlags(terms);
  cv::Size size = data.size;
  if (start != nullptr) {
    fit.matrix = start->matrix.clone();
    fit.distortion = start->distortion.clone();
    flags |= cv::CALIB_USE_INTRINSIC_GUESS;
    size = sizeHolding(size, fit.matrix);
  }
  try {
    std::vector<cv::Mat> rvecs, tvecs;
    cv::Mat extrinsic_sd, per_view;
    fit.rms = cv::calibrateCamera(data.objects, data.images, size, fit.matrix, fit.distortion, rvecs, tvecs, fit.sd,
                                  extrinsic_sd, per_view, flags);
    fit.board_normals = boardNormals(rvecs);
  } catch (const cv::Exception& e) {
    throw core::Error(std::string("calibrate rig: OpenCV could not calibrate the ") + data.device + ": " + e.err);
  }
  if (!std::isfinite(fit.rms)) {
    throw core::Error(std::string("calibrate rig: the ") + data.device + "'s solve did not converge");
  }
  return fit;
}

// OpenCV's solve started from zero distortion with k3 free runs off to a k3 of the order of 1 (a
// worse fit than with k3 held): k3 is freed only from the fit that held it.
LensFit scratchFit(const LensData& data, const DistortionTerms& terms) {
  DistortionTerms without_k3 = terms;
  without_k3.k3 = false;
  const LensFit held = calibrateLens(data, without_k3);
  return terms.k3 ? calibrateLens(data, terms, &held) : held;
}

double sdAt(const cv::Mat& sd, int i) { return i < static_cast<int>(sd.total()) ? sd.at<double>(i) : 0.0; }

// The distortion vector's entries of term `index` (kDistortionTermNames): k1, k2, p1 p2, k3.
std::array<int, 2> termEntries(int index) {
  constexpr std::array<std::array<int, 2>, kDistortionTermCount> entries{{{0, -1}, {1, -1}, {2, 3}, {4, -1}}};
  return entries[static_cast<std::size_t>(index)];
}

double largestAngleDeg(const std::vector<Eigen::Vector3d>& normals) {
  double largest = 0.0;
  for (std::size_t a = 0; a < normals.size(); ++a) {
    for (std::size_t b = a + 1; b < normals.size(); ++b) {
      const double cosine = std::clamp(normals[a].normalized().dot(normals[b].normalized()), -1.0, 1.0);
      largest = std::max(largest, std::acos(cosine) * kDegreesPerRadian);
    }
  }
  return largest;
}

void recordTerm(const LensFit& fitted, int term, TermResidual& residual) {
  residual.rms_fitted_px = fitted.rms;
  const std::array<int, 2> entries = termEntries(term);
  for (std::size_t k = 0; k < 2 && entries[k] >= 0; ++k) {
    residual.value[k] = fitted.distortion.at<double>(entries[k]);
    residual.sd[k] = sdAt(fitted.sd, 4 + entries[k]);
  }
}

}  // namespace

LensFit fitLensReported(const LensData& data, const DistortionTerms& terms, LensFitReport& report) {
  report = LensFitReport{};
  report.terms = terms;
  LensFit fit = scratchFit(data, terms);
  report.scratch_rms_px = fit.rms;
  // Each chosen term held (a fresh solve with one term fewer): the report's "held" figures, and
  // the starts for the richer model where it ended worse than one of them.
  std::array<LensFit, kDistortionTermCount> held;
  for (int term = 0; term < kDistortionTermCount; ++term) {
    if (!terms.fits(term)) continue;
    held[static_cast<std::size_t>(term)] = scratchFit(data, terms.with(term, false));
  }
  for (int term = 0; term < kDistortionTermCount; ++term) {
    const LensFit& start = held[static_cast<std::size_t>(term)];
    if (!terms.fits(term) || !(start.rms < fit.rms)) continue;
    LensFit restarted = calibrateLens(data, terms, &start);
    if (restarted.rms < fit.rms) {
      fit = std::move(restarted);
      report.restarted_from = kDistortionTermNames[static_cast<std::size_t>(term)];
    }
  }
  // Should the restart too end above a fit with one term fewer, that fit is one of the richer
  // model's (the term at 0) and the better one.
  for (int term = 0; term < kDistortionTermCount; ++term) {
    const LensFit& start = held[static_cast<std::size_t>(term)];
    if (!terms.fits(term) || !(start.rms < fit.rms)) continue;
    fit = start;
    report.restarted_from = kDistortionTermNames[static_cast<std::size_t>(term)];
  }
  report.rms_px = fit.rms;
  for (int i = 0; i < 9; ++i) report.sd[static_cast<std::size_t>(i)] = sdAt(fit.sd, i);
  report.board_normal_spread_deg = largestAngleDeg(fit.board_normals);
  for (int term = 0; term < kDistortionTermCount; ++term) {
    TermResidual& residual = report.per_term[static_cast<std::size_t>(term)];
    residual.chosen = terms.fits(term);
    if (residual.chosen) {
      recordTerm(fit, term, residual);
      residual.rms_held_px = held[static_cast<std::size_t>(term)].rms;
    } else {
      // Freed from the fit: freeing can only lower the RMS.
      recordTerm(calibrateLens(data, terms.with(term, true), &fit), term, residual);
      residual.rms_held_px = fit.rms;
    }
  }
  return fit;
}

io::LensIntrinsics lensFrom(const LensFit& fit, cv::Size size) {
  io::LensIntrinsics lens;
  lens.width = size.width;
  lens.height = size.height;
  lens.fx = fit.matrix.at<double>(0, 0);
  lens.fy = fit.matrix.at<double>(1, 1);
  lens.cx = fit.matrix.at<double>(0, 2);
  lens.cy = fit.matrix.at<double>(1, 2);
  for (int i = 0; i < 5; ++i) lens.distortion[static_cast<std::size_t>(i)] = fit.distortion.at<double>(i);
  return lens;
}

}  // namespace binpick::calibration::detail
