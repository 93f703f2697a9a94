// calibrateRig: usable views, one solve, outliers flagged (and optionally dropped, one more solve).
#include "binpick/calibration/rig_calibrator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "binpick/core/error.hpp"
#include "binpick/io/capture.hpp"
#include "rig_diagnosis.hpp"
#include "rig_solver.hpp"
#include "rig_view_triage.hpp"

namespace binpick::calibration {
namespace {

double median(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// One solve over some of the views, and which of them stand out.
struct Attempt {
  std::vector<std::size_t> views;  // indices into the views given
  detail::RigSolution solution;
  std::vector<bool> outlier;  // per entry of `views`
  double camera_limit_px = 0.0;
  double projector_limit_px = 0.0;
};

Attempt solve(const std::vector<RigView>& views, const std::vector<std::size_t>& indices, const BoardLayout& layout,
              const RigCalibrationParams& params) {
  Attempt attempt;
  attempt.views = indices;
  std::vector<detail::ViewPoints> points;
  for (const std::size_t i : indices) points.push_back(detail::viewPoints(views[i], layout));
  const RigView& first = views[indices.front()];
  attempt.solution = detail::solveRig(points, {first.camera_width, first.camera_height},
                                      {first.projector_width, first.projector_height}, params);
  const detail::RigSolution& s = attempt.solution;
  attempt.camera_limit_px = std::max(params.outlier_floor_px, params.outlier_factor * median(s.view_camera_rms_px));
  attempt.projector_limit_px =
      std::max(params.outlier_floor_px, params.outlier_factor * median(s.view_projector_rms_px));
  for (std::size_t k = 0; k < indices.size(); ++k) {
    attempt.outlier.push_back(s.view_camera_rms_px[k] > attempt.camera_limit_px ||
                              s.view_projector_rms_px[k] > attempt.projector_limit_px);
  }
  return attempt;
}

std::string outlierText(const Attempt& attempt, std::size_t k, const std::string& name) {
  char text[256];
  std::snprintf(text, sizeof text, ": outlier: RMS camera %.2f px, projector %.2f px (limits %.2f, %.2f px)",
                attempt.solution.view_camera_rms_px[k], attempt.solution.view_projector_rms_px[k],
                attempt.camera_limit_px, attempt.projector_limit_px);
  return name + text;
}

// Writes each view of the attempt into the quality table: its RMS, whether it stands out, and
// whether it went into the calibration.
void recordViews(const Attempt& attempt, bool used, io::RigCalibrationQuality& quality) {
  for (std::size_t k = 0; k < attempt.views.size(); ++k) {
    io::RigViewQuality& view = quality.views[attempt.views[k]];
    view.camera_rms_px = attempt.solution.view_camera_rms_px[k];
    view.projector_rms_px = attempt.solution.view_projector_rms_px[k];
    view.outlier = attempt.outlier[k];
    view.used = used;
  }
}

std::vector<std::size_t> withoutOutliers(const Attempt& attempt) {
  std::vector<std::size_t> kept;
  for (std::size_t k = 0; k < attempt.views.size(); ++k) {
    if (!attempt.outlier[k]) kept.push_back(attempt.views[k]);
  }
  return kept;
}

}  // namespace

void RigCalibrationParams::validate() const {
  const std::string owner = "RigCalibrationParams";
  core::requireField(min_views >= 3, owner, "min_views", ">= 3", min_views);
  core::requireField(recommended_views >= 3, owner, "recommended_views", ">= 3", recommended_views);
  core::requireField(std::isfinite(max_focal_sd_share) && max_focal_sd_share > 0.0, owner, "max_focal_sd_share",
                     "positive", max_focal_sd_share);
  core::requireField(std::isfinite(max_principal_point_sd_share) && max_principal_point_sd_share > 0.0, owner,
                     "max_principal_point_sd_share", "positive", max_principal_point_sd_share);
  core::requireField(min_corners >= 6, owner, "min_corners", ">= 6", min_corners);
  core::requireField(std::isfinite(outlier_floor_px) && outlier_floor_px >= 0.0, owner, "outlier_floor_px", ">= 0",
                     outlier_floor_px);
  core::requireField(std::isfinite(outlier_factor) && outlier_factor >= 1.0, owner, "outlier_factor", ">= 1",
                     outlier_factor);
  core::requireField(std::isfinite(warn_rms_px) && warn_rms_px > 0.0, owner, "warn_rms_px", "positive", warn_rms_px);
}

RigCalibrationResult calibrateRig(const std::vector<RigView>& views, const BoardLayout& layout,
                                  const RigCalibrationParams& params) {
  params.validate();
  layout.validate();
  RigCalibrationResult result;
  std::vector<std::string> problems;
  std::vector<std::size_t> usable;
  for (std::size_t i = 0; i < views.size(); ++i) {
    const RigView& view = views[i];
    io::RigViewQuality quality;
    quality.name = view.name;
    quality.camera_corners = static_cast<int>(view.board.ids.size());
    quality.projector_corners = static_cast<int>(view.projector.corners.size());
    quality.problem = detail::viewProblem(view, params);
    problems.push_back(quality.problem);
    if (quality.problem.empty()) {
      usable.push_back(i);
      for (std::string& w : detail::viewWarnings(view)) result.warnings.push_back(std::move(w));
    } else {
      result.warnings.push_back(view.name + ": skipped: " + quality.problem);
    }
    result.quality.views.push_back(std::move(quality));
  }
  if (static_cast<int>(usable.size()) < params.min_views) {
    throw core::Error(detail::tooFewViewsMessage(views, problems, static_cast<int>(usable.size()), params.min_views));
  }
  detail::requireSameSizes(views, usable);

  Attempt attempt = solve(views, usable, layout, params);
  const std::vector<std::size_t> kept = withoutOutliers(attempt);
  if (params.drop_outliers && kept.size() < usable.size()) {
    if (static_cast<int>(kept.size()) < params.min_views) {
      throw core::Error("calibrate rig: dropping the " + std::to_string(usable.size() - kept.size()) +
                        " outlier views would leave " + std::to_string(kept.size()) + " views, fewer than the " +
                        std::to_string(params.min_views) + " needed; capture more views");
    }
    recordViews(attempt, false, result.quality);
    for (std::size_t k = 0; k < attempt.views.size(); ++k) {
      if (!attempt.outlier[k]) continue;
      const std::string& name = views[attempt.views[k]].name;
      result.quality.views[attempt.views[k]].problem = "outlier, dropped";
      result.warnings.push_back(outlierText(attempt, k, name) + "; dropped");
    }
    attempt = solve(views, kept, layout, params);
  }
  recordViews(attempt, true, result.quality);
  for (std::size_t k = 0; k < attempt.views.size(); ++k) {
    if (!attempt.outlier[k]) continue;
    result.warnings.push_back(
        outlierText(attempt, k, views[attempt.views[k]].name) +
        (params.drop_outliers ? "; kept (outliers are dropped once)" : "; kept: capture it again, or drop outliers"));
  }

  const detail::RigSolution& solution = attempt.solution;
  result.rig = solution.rig;
  result.camera_fit = solution.camera_fit;
  result.projector_fit = solution.projector_fit;
  result.timings = solution.timings;
  result.quality.date = io::utcTimestamp();
  result.quality.camera_rms_px = solution.camera_rms_px;
  result.quality.projector_rms_px = solution.projector_rms_px;
  result.quality.stereo_rms_px = solution.stereo_rms_px;
  if (!(solution.stereo_rms_px <= params.warn_rms_px)) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "the calibration's stereo RMS is %.2f px, above %.2f px: check the focus, the"
                  " board's flatness and that it stood still in every view",
                  solution.stereo_rms_px, params.warn_rms_px);
    result.warnings.push_back(text);
  }
  const double span = detail::meanBoardSpan(views, attempt.views);
  for (std::string& warning : detail::geometryWarnings(result, static_cast<int>(attempt.views.size()), span, params)) {
    result.warnings.push_back(std::move(warning));
  }
  return result;
}

}  // namespace binpick::calibration
