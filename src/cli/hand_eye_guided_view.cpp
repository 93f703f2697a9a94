// One view of a guided session: the pose journaled, the image taken, checked as the file mode
// will check it, and filed as a view or as a rejected attempt. One log line per view.
#include <spdlog/spdlog.h>

#include <exception>

#include "binpick/core/error.hpp"
#include "hand_eye_guided_session.hpp"

namespace binpick::cli {
namespace {

using robot::Status;

bool matchesCalibration(const cv::Mat& image, const io::LensIntrinsics& camera) {
  return image.cols == camera.width && image.rows == camera.height;
}

}  // namespace

Status HandEyeGuidedSession::takeView(const Job& job) {
  const int wanted = params_.wanted;
  try {
    const std::string attempt = recorder_.receive(job.T_base_flange);
    cv::Mat image;
    try {
      image = camera_.grab();
    } catch (const core::Error& error) {
      spdlog::warn("{}: no image: {} ({} of {} views)", attempt, error.what(), recorder_.accepted(), wanted);
      return Status::NoImage;
    }
    const std::string staged = recorder_.stage(image);
    if (!matchesCalibration(image, params_.camera)) {
      const std::string kept = recorder_.reject(attempt, job.T_base_flange);
      spdlog::warn(
          "{}: the image is {}x{} but the camera calibration is {}x{}: wrong --calib or "
          "camera ({} kept; {} of {} views)",
          attempt, image.cols, image.rows, params_.camera.width, params_.camera.height, kept, recorder_.accepted(),
          wanted);
      return Status::CalibrationMissing;
    }
    calibration::MeasuredView view;
    try {
      view = calibration::measureView({attempt, job.T_base_flange, staged, {}}, params_.layout, params_.camera,
                                      params_.check);
    } catch (const core::Error& error) {
      view.problem = error.what();  // an image the check cannot read: no board in it either
    }
    if (!view.usable()) {
      const std::string kept = recorder_.reject(attempt, job.T_base_flange);
      spdlog::warn("{}: rejected: {} ({} kept; {} of {} views)", attempt, view.problem, kept, recorder_.accepted(),
                   wanted);
      return Status::BoardNotFound;
    }
    const std::string name = recorder_.accept(job.T_base_flange);
    spdlog::info("{}: accepted as {}: {} of {} corners, {:.2f} px RMS{}{} ({} of {} views)", attempt, name,
                 view.corners, view.expected, view.rms_px, view.note.empty() ? "" : "; ", view.note,
                 recorder_.accepted(), wanted);
    return Status::Ok;
  } catch (const std::exception& error) {
    // A view that cannot be written (disk full, permissions): the robot hears of it at once.
    spdlog::error("the view of client {} could not be recorded: {}", job.client, error.what());
    return Status::InternalError;
  }
}

}  // namespace binpick::cli
