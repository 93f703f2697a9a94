// Warnings about what the views leave poorly determined.
#include "rig_diagnosis.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace binpick::calibration::detail {
namespace {

std::string formatted(const char* pattern, double a, double b = 0.0) {
  char text[96];
  std::snprintf(text, sizeof text, pattern, a, b);
  return text;
}

// The poorly determined intrinsics of one device, comma-separated.
std::string deviceList(const LensFitReport& fit, const io::LensIntrinsics& lens, const RigCalibrationParams& params) {
  std::vector<std::string> items;
  const double focal_limit = params.max_focal_sd_share;
  if (fit.sd[0] > focal_limit * lens.fx) items.push_back(formatted("fx +- %.1f px", fit.sd[0]));
  if (fit.sd[1] > focal_limit * lens.fy) items.push_back(formatted("fy +- %.1f px", fit.sd[1]));
  const double centre_limit = params.max_principal_point_sd_share * lens.width;
  if (fit.sd[2] > centre_limit) items.push_back(formatted("cx +- %.1f px", fit.sd[2]));
  if (fit.sd[3] > centre_limit) items.push_back(formatted("cy +- %.1f px", fit.sd[3]));
  // A fitted distortion term whose deviation exceeds its value: the views cannot tell it from 0.
  constexpr const char* kNames[5] = {"k1", "k2", "p1", "p2", "k3"};
  for (int i = 0; i < 5; ++i) {
    const double sd = fit.sd[static_cast<std::size_t>(4 + i)];
    const double value = lens.distortion[static_cast<std::size_t>(i)];
    if (sd > 0.0 && sd > std::abs(value)) {
      items.push_back(std::string(kNames[i]) + formatted(" %.4f +- %.4f", value, sd));
    }
  }
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
  return text;
}

}  // namespace

bool principalPointPoorlyPinned(const LensFitReport& fit, int image_width, const RigCalibrationParams& params) {
  const double limit = params.max_principal_point_sd_share * image_width;
  return fit.sd[2] > limit || fit.sd[3] > limit;
}

std::string poorlyDetermined(const RigCalibrationResult& result, const RigCalibrationParams& params) {
  // The own solves' values beside their deviations: the stereo step's may have moved.
  const std::string camera = deviceList(result.camera_fit, result.camera_fit.lens, params);
  const std::string projector = deviceList(result.projector_fit, result.projector_fit.lens, params);
  std::string text;
  if (!camera.empty()) text = "camera " + camera;
  if (!projector.empty()) text += (text.empty() ? "projector " : "; projector ") + projector;
  return text;
}

double meanBoardSpan(const std::vector<RigView>& views, const std::vector<std::size_t>& used) {
  double sum = 0.0;
  int counted = 0;
  for (const std::size_t i : used) {
    const RigView& view = views[i];
    if (view.board.pixels.empty() || view.camera_width <= 0) continue;
    const auto [low, high] =
        std::minmax_element(view.board.pixels.begin(), view.board.pixels.end(),
                            [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() < b.x(); });
    sum += (high->x() - low->x()) / view.camera_width;
    ++counted;
  }
  return counted > 0 ? sum / counted : 0.0;
}

std::vector<std::string> geometryWarnings(const RigCalibrationResult& result, int views_used, double board_span,
                                          const RigCalibrationParams& params) {
  std::vector<std::string> warnings;
  if (views_used < params.recommended_views) {
    const std::string poor = poorlyDetermined(result, params);
    std::ostringstream text;
    text << "only " << views_used << " views used, " << params.recommended_views
         << " or more recommended: poorly determined (own solves' standard deviations): "
         << (poor.empty() ? "nothing" : poor) << "; capture more views";
    warnings.push_back(text.str());
  }
  const bool camera = principalPointPoorlyPinned(result.camera_fit, result.rig.camera.width, params);
  const bool projector = principalPointPoorlyPinned(result.projector_fit, result.rig.projector.width, params);
  if (camera || projector) {
    const LensFitReport& c = result.camera_fit;
    const LensFitReport& p = result.projector_fit;
    // Far or narrow views leave little perspective to separate the principal point from the
    // board's pose: tilt helps, and so does a board filling more of the image.
    std::string remedy;
    if (c.board_normal_spread_deg < params.min_tilt_spread_deg)
      remedy = "tilt the board more (30-40 degrees in different directions)";
    if (board_span < params.min_board_span) {
      remedy += std::string(remedy.empty() ? "" : " and ") +
                "bring the board closer (or use a larger one) so that it fills more of the image";
    }
    if (remedy.empty()) remedy = "add views with the board tilted in other directions and near the image's corners";
    char text[640];
    std::snprintf(text, sizeof text,
                  "the views do not pin the principal points (camera cx, cy +- %.1f, %.1f px; projector +- %.1f,"
                  " %.1f px): the board's tilt differs by at most %.0f degrees between views and it spans %.0f%% of"
                  " the image's width; the stereo step moved the camera's by %.1f, %.1f px and the projector's by"
                  " %.1f, %.1f px: ",
                  c.sd[2], c.sd[3], p.sd[2], p.sd[3], c.board_normal_spread_deg, 100.0 * board_span,
                  result.rig.camera.cx - c.lens.cx, result.rig.camera.cy - c.lens.cy,
                  result.rig.projector.cx - p.lens.cx, result.rig.projector.cy - p.lens.cy);
    warnings.push_back(text + remedy);
  }
  return warnings;
}

}  // namespace binpick::calibration::detail
