// Camera, projector and stereo solves with OpenCV's calibration functions.
#include "rig_solver.hpp"

#include <array>
#include <cmath>
#include <opencv2/calib3d.hpp>

#include "binpick/core/error.hpp"
#include "binpick/core/stopwatch.hpp"
#include "cv_eigen.hpp"

namespace binpick::calibration::detail {
namespace {

cv::Point3f objectPoint(const BoardLayout& layout, int id) {
  const Eigen::Vector3d p = layout.cornerPoint(id);
  return {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
}

cv::Point2f imagePoint(const Eigen::Vector2d& pixel) {
  return {static_cast<float>(pixel.x()), static_cast<float>(pixel.y())};
}

struct LensFit {
  cv::Mat matrix;
  cv::Mat distortion;
  double rms = 0.0;
  cv::Mat sd;  // standard deviations of the intrinsics, OpenCV's order
};

// OpenCV's flags holding the terms not in `terms` (at 0: there is no intrinsic guess here).
int heldTermFlags(const DistortionTerms& terms) {
  return (terms.k1 ? 0 : cv::CALIB_FIX_K1) | (terms.k2 ? 0 : cv::CALIB_FIX_K2) |
         (terms.tangential ? 0 : cv::CALIB_ZERO_TANGENT_DIST) | (terms.k3 ? 0 : cv::CALIB_FIX_K3);
}

// With a `start`, from its intrinsics (CALIB_USE_INTRINSIC_GUESS).
LensFit calibrateLens(const std::vector<std::vector<cv::Point3f>>& objects,
                      const std::vector<std::vector<cv::Point2f>>& images, cv::Size size, const DistortionTerms& terms,
                      const char* device, const LensFit* start = nullptr) {
  LensFit fit;
  int flags = heldTermFlags(terms);
  if (start != nullptr) {
    fit.matrix = start->matrix.clone();
    fit.distortion = start->distortion.clone();
    flags |= cv::CALIB_USE_INTRINSIC_GUESS;
  }
  try {
    std::vector<cv::Mat> rvecs, tvecs;
    cv::Mat extrinsic_sd, per_view;
    fit.rms = cv::calibrateCamera(objects, images, size, fit.matrix, fit.distortion, rvecs, tvecs, fit.sd, extrinsic_sd,
                                  per_view, flags);
  } catch (const cv::Exception& e) {
    throw core::Error(std::string("calibrate rig: OpenCV could not calibrate the ") + device + ": " + e.err);
  }
  return fit;
}

// OpenCV's solve started from zero distortion with k3 free runs off to a k3 of the order of 1 (a
// worse fit than with k3 held): k3 is freed only from the fit that held it.
LensFit fitLens(const std::vector<std::vector<cv::Point3f>>& objects,
                const std::vector<std::vector<cv::Point2f>>& images, cv::Size size, const DistortionTerms& terms,
                const char* device) {
  DistortionTerms without_k3 = terms;
  without_k3.k3 = false;
  const LensFit held = calibrateLens(objects, images, size, without_k3, device);
  return terms.k3 ? calibrateLens(objects, images, size, terms, device, &held) : held;
}

double sdAt(const cv::Mat& sd, int i) { return i < static_cast<int>(sd.total()) ? sd.at<double>(i) : 0.0; }

// The distortion vector's entries of term `index` (kDistortionTermNames): k1, k2, p1 p2, k3.
std::array<int, 2> termEntries(int index) {
  constexpr std::array<std::array<int, 2>, kDistortionTermCount> entries{{{0, -1}, {1, -1}, {2, 3}, {4, -1}}};
  return entries[static_cast<std::size_t>(index)];
}

// The chosen fit, and per term the same solve with that term toggled: held (a fresh solve) when
// the fit has it, freed from the fit when it does not, so that freeing can only lower the RMS.
LensFitReport reportLens(const LensFit& fit, const std::vector<std::vector<cv::Point3f>>& objects,
                         const std::vector<std::vector<cv::Point2f>>& images, cv::Size size,
                         const DistortionTerms& terms, const char* device) {
  LensFitReport report;
  report.terms = terms;
  report.rms_px = fit.rms;
  for (int i = 0; i < 9; ++i) report.sd[i] = sdAt(fit.sd, i);
  for (int term = 0; term < kDistortionTermCount; ++term) {
    TermResidual& residual = report.per_term[static_cast<std::size_t>(term)];
    residual.chosen = terms.fits(term);
    const DistortionTerms toggled = terms.with(term, !residual.chosen);
    const LensFit other = residual.chosen ? fitLens(objects, images, size, toggled, device)
                                          : calibrateLens(objects, images, size, toggled, device, &fit);
    const LensFit& fitted = residual.chosen ? fit : other;
    residual.rms_fitted_px = fitted.rms;
    residual.rms_held_px = residual.chosen ? other.rms : fit.rms;
    const std::array<int, 2> entries = termEntries(term);
    for (std::size_t k = 0; k < 2 && entries[k] >= 0; ++k) {
      residual.value[k] = fitted.distortion.at<double>(entries[k]);
      residual.sd[k] = sdAt(fitted.sd, 4 + entries[k]);
    }
  }
  return report;
}

io::LensIntrinsics lensFrom(const LensFit& fit, cv::Size size) {
  io::LensIntrinsics lens;
  lens.width = size.width;
  lens.height = size.height;
  lens.fx = fit.matrix.at<double>(0, 0);
  lens.fy = fit.matrix.at<double>(1, 1);
  lens.cx = fit.matrix.at<double>(0, 2);
  lens.cy = fit.matrix.at<double>(1, 2);
  for (int i = 0; i < 5; ++i) lens.distortion[i] = fit.distortion.at<double>(i);
  return lens;
}

}  // namespace

ViewPoints viewPoints(const RigView& view, const BoardLayout& layout) {
  ViewPoints points;
  for (std::size_t i = 0; i < view.board.ids.size(); ++i) {
    points.camera_object.push_back(objectPoint(layout, view.board.ids[i]));
    points.camera_image.push_back(imagePoint(view.board.pixels[i]));
  }
  for (const ProjectorCorner& corner : view.projector.corners) {
    points.shared_object.push_back(objectPoint(layout, corner.id));
    points.shared_camera.push_back(imagePoint(corner.camera));
    points.shared_projector.push_back(imagePoint(corner.projector));
  }
  return points;
}

RigSolution solveRig(const std::vector<ViewPoints>& views, cv::Size camera_size, cv::Size projector_size,
                     const RigCalibrationParams& params) {
  std::vector<std::vector<cv::Point3f>> camera_object, shared_object;
  std::vector<std::vector<cv::Point2f>> camera_image, shared_camera, shared_projector;
  for (const ViewPoints& view : views) {
    camera_object.push_back(view.camera_object);
    camera_image.push_back(view.camera_image);
    shared_object.push_back(view.shared_object);
    shared_camera.push_back(view.shared_camera);
    shared_projector.push_back(view.shared_projector);
  }
  RigSolution solution;
  core::Stopwatch stage;
  LensFit camera = fitLens(camera_object, camera_image, camera_size, params.camera_distortion, "camera");
  solution.camera_fit =
      reportLens(camera, camera_object, camera_image, camera_size, params.camera_distortion, "camera");
  solution.timings.camera = stage.lapMs();
  LensFit projector =
      fitLens(shared_object, shared_projector, projector_size, params.projector_distortion, "projector");
  solution.projector_fit =
      reportLens(projector, shared_object, shared_projector, projector_size, params.projector_distortion, "projector");
  solution.timings.projector = stage.lapMs();

  // stereoCalibrate's flags hold a term for both devices at once: a term either device holds is
  // held, at the value of each device's own solve (the intrinsic guess).
  const DistortionTerms& a = params.camera_distortion;
  const DistortionTerms& b = params.projector_distortion;
  const DistortionTerms both{a.k1 && b.k1, a.k2 && b.k2, a.tangential && b.tangential, a.k3 && b.k3};
  int flags = cv::CALIB_FIX_INTRINSIC;
  if (params.refine_intrinsics_in_stereo) {
    flags = cv::CALIB_USE_INTRINSIC_GUESS | (heldTermFlags(both) & ~cv::CALIB_ZERO_TANGENT_DIST) |
            (both.tangential ? 0 : cv::CALIB_FIX_TANGENT_DIST);
  }
  cv::Mat r, t, essential, fundamental, per_view;
  const cv::TermCriteria criteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-10);
  try {
    solution.stereo_rms_px = cv::stereoCalibrate(shared_object, shared_camera, shared_projector, camera.matrix,
                                                 camera.distortion, projector.matrix, projector.distortion, camera_size,
                                                 r, t, essential, fundamental, per_view, flags, criteria);
  } catch (const cv::Exception& e) {
    throw core::Error("calibrate rig: OpenCV could not solve the camera-projector pose: " + e.err);
  }
  solution.timings.stereo = stage.lapMs();

  solution.camera_rms_px = camera.rms;
  solution.projector_rms_px = projector.rms;
  solution.rig.camera = lensFrom(camera, camera_size);
  solution.rig.projector = lensFrom(projector, projector_size);
  solution.rig.T_projector_camera = detail::isometryFromCv(r, t);
  if (per_view.rows != static_cast<int>(views.size()) || per_view.cols != 2 || !std::isfinite(solution.stereo_rms_px) ||
      !std::isfinite(camera.rms) || !std::isfinite(projector.rms)) {
    throw core::Error("calibrate rig: the solve did not converge (no finite reprojection errors)");
  }
  for (int v = 0; v < per_view.rows; ++v) {
    solution.view_camera_rms_px.push_back(per_view.at<double>(v, 0));
    solution.view_projector_rms_px.push_back(per_view.at<double>(v, 1));
  }
  try {
    solution.rig.validate();
  } catch (const core::Error& e) {
    throw core::Error(std::string("calibrate rig: the solved rig is not valid: ") + e.what());
  }
  return solution;
}

}  // namespace binpick::calibration::detail
