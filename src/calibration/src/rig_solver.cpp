// Camera, projector and stereo solves with OpenCV's calibration functions.
#include "rig_solver.hpp"

#include <array>
#include <cmath>
#include <opencv2/calib3d.hpp>

#include "binpick/core/error.hpp"
#include "binpick/core/stopwatch.hpp"
#include "cv_eigen.hpp"
#include "lens_fit.hpp"

namespace binpick::calibration::detail {
namespace {

cv::Point3f objectPoint(const BoardLayout& layout, int id) {
  const Eigen::Vector3d p = layout.cornerPoint(id);
  return {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
}

cv::Point2f imagePoint(const Eigen::Vector2d& pixel) {
  return {static_cast<float>(pixel.x()), static_cast<float>(pixel.y())};
}

// OpenCV's flags holding the terms not in `terms`, for the stereo step.
int heldTermFlags(const DistortionTerms& terms) {
  return (terms.k1 ? 0 : cv::CALIB_FIX_K1) | (terms.k2 ? 0 : cv::CALIB_FIX_K2) |
         (terms.tangential ? 0 : cv::CALIB_ZERO_TANGENT_DIST) | (terms.k3 ? 0 : cv::CALIB_FIX_K3);
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
  LensFit camera = fitLensReported({camera_object, camera_image, camera_size, "camera"}, params.camera_distortion,
                                   solution.camera_fit);
  solution.camera_fit.lens = lensFrom(camera, camera_size);
  solution.timings.camera = stage.lapMs();
  LensFit projector = fitLensReported({shared_object, shared_projector, projector_size, "projector"},
                                      params.projector_distortion, solution.projector_fit);
  solution.projector_fit.lens = lensFrom(projector, projector_size);
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
