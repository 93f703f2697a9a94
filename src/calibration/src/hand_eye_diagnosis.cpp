// What a poor hand-eye fit is likely to mean: robot positions in metres, one view that
// disagrees with the others, a wrong board size. Each is tested by solving again with the
// suspected mistake undone; the linear solver alone (solveQuickly), as these take many solves.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "binpick/core/error.hpp"
#include "hand_eye_internal.hpp"

namespace binpick::calibration::detail {
namespace {

constexpr double kMillimetresPerMetre = 1000.0;
constexpr double kMadToSigma = 1.4826;  // MAD to a normal distribution's standard deviation
// Fewer views leave no residual to judge the left-out one by (OpenCV needs 3).
constexpr std::size_t kFewestForLeaveOneOut = 5;
// The board scales searched: a wrong square size, a board printed at another scale.
constexpr double kSmallestScale = 0.8;
constexpr double kLargestScale = 1.25;
constexpr int kScaleIterations = 40;
// A scale counts when it fits this many times better and is this far from 1.
constexpr double kScaleFitRatio = 2.0;
constexpr double kSmallestScaleError = 0.003;

std::string describe(const PoseDifference& rms) {
  std::ostringstream text;
  text.precision(3);
  text << rms.translation_mm << " mm, " << rms.rotation_deg << " deg RMS";
  return text.str();
}

// The RMS of the quick solution, or infinity when there is none.
PoseDifference quickFit(const std::vector<HandEyeView>& views, const HandEyeParams& params) {
  try {
    const HandEyeProblem problem = makeProblem(views, params.setup, false);
    return rmsOf(residualsOf(problem, solveQuickly(problem, params)));
  } catch (const core::Error&) {
    const double infinity = std::numeric_limits<double>::infinity();
    return {infinity, infinity};
  }
}

double median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// The value above which one of `values` stands far above the rest.
double robustLimit(const std::vector<double>& values, const HandEyeParams& params, double floor) {
  const double middle = median(values);
  std::vector<double> deviations;
  for (const double v : values) deviations.push_back(std::abs(v - middle));
  const double sigma = kMadToSigma * median(deviations);
  return std::max({middle + params.outlier_mad_factor * sigma, params.outlier_factor * middle, floor});
}

std::vector<HandEyeView> withBoardScaled(std::vector<HandEyeView> views, double scale) {
  for (HandEyeView& view : views) view.T_camera_board.translation() *= scale;
  return views;
}

// Golden-section search for the board scale that fits best.
double bestBoardScale(const std::vector<HandEyeView>& views, const HandEyeParams& params) {
  const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
  double low = kSmallestScale, high = kLargestScale;
  auto cost = [&](double s) { return quickFit(withBoardScaled(views, s), params).translation_mm; };
  double a = high - ratio * (high - low), b = low + ratio * (high - low);
  double cost_a = cost(a), cost_b = cost(b);
  for (int i = 0; i < kScaleIterations; ++i) {
    if (cost_a < cost_b) {
      high = b;
      b = a;
      cost_b = cost_a;
      a = high - ratio * (high - low);
      cost_a = cost(a);
    } else {
      low = a;
      a = b;
      cost_a = cost_b;
      b = low + ratio * (high - low);
      cost_b = cost(b);
    }
  }
  return 0.5 * (low + high);
}

}  // namespace

void rejectPositionsInMetres(const std::vector<HandEyeView>& views, const HandEyeParams& params,
                             const PoseDifference& as_given) {
  if (!(as_given.translation_mm > params.max_rms_mm && as_given.rotation_deg <= params.max_rms_deg)) return;
  std::vector<HandEyeView> scaled = views;
  for (HandEyeView& view : scaled) view.T_base_flange.translation() *= kMillimetresPerMetre;
  const PoseDifference fit = quickFit(scaled, params);
  if (!(fit.translation_mm <= params.max_rms_mm &&
        fit.translation_mm * params.inverted_fit_ratio < as_given.translation_mm)) {
    return;
  }
  throw core::Error("hand-eye: units? the robot positions look like metres, expected millimetres: the rotations fit (" +
                    describe(as_given) + " as given) and multiplied by 1000 the positions fit to " + describe(fit) +
                    "; write x y z in millimetres");
}

std::vector<HandEyeResidual> leaveOneOutResiduals(const std::vector<HandEyeView>& views, const HandEyeParams& params) {
  std::vector<HandEyeResidual> residuals;
  if (views.size() < kFewestForLeaveOneOut) return residuals;
  for (std::size_t i = 0; i < views.size(); ++i) {
    std::vector<HandEyeView> others = views;
    others.erase(others.begin() + static_cast<std::ptrdiff_t>(i));
    HandEyeResidual r;
    r.name = views[i].name;
    try {
      const MountTransforms mounts = solveQuickly(makeProblem(others, params.setup, false), params);
      r = residualsOf(makeProblem({views[i]}, params.setup, false), mounts).front();
    } catch (const core::Error&) {
      r.translation_mm = r.rotation_deg = 0.0;  // the others alone do not solve: no judgement
    }
    residuals.push_back(r);
  }
  return residuals;
}

std::vector<std::size_t> disagreeingViews(const std::vector<HandEyeResidual>& left_out, const HandEyeParams& params) {
  std::vector<std::size_t> suspects;
  if (left_out.empty()) return suspects;
  std::vector<double> mm, deg;
  for (const HandEyeResidual& r : left_out) {
    mm.push_back(r.translation_mm);
    deg.push_back(r.rotation_deg);
  }
  const double mm_limit = robustLimit(mm, params, params.outlier_floor_mm);
  const double deg_limit = robustLimit(deg, params, params.outlier_floor_deg);
  for (std::size_t i = 0; i < left_out.size(); ++i) {
    if (left_out[i].translation_mm > mm_limit || left_out[i].rotation_deg > deg_limit) suspects.push_back(i);
  }
  return suspects;
}

std::string boardSizeWarning(const std::vector<HandEyeView>& views, const HandEyeParams& params,
                             const PoseDifference& as_given) {
  if (!(as_given.translation_mm > params.outlier_floor_mm)) return "";
  const PoseDifference unscaled = quickFit(views, params);
  const double scale = bestBoardScale(views, params);
  const PoseDifference scaled = quickFit(withBoardScaled(views, scale), params);
  std::ostringstream text;
  text.precision(3);
  if (scaled.translation_mm * kScaleFitRatio < unscaled.translation_mm && std::abs(scale - 1.0) > kSmallestScaleError) {
    text << "the board size looks wrong: the residual is " << describe(as_given) << ", and with the board "
         << std::abs(scale - 1.0) * 100.0 << "% " << (scale > 1.0 ? "larger" : "smaller") << " (scale " << scale
         << ") the views fit to " << describe(scaled)
         << "; check the square size (--square-mm) against the printed board: a 1% size error costs millimetres";
    return text.str();
  }
  if (as_given.translation_mm > params.warn_rms_mm) {
    text << "the residual RMS " << describe(as_given) << " is large for a robot (above " << params.warn_rms_mm
         << " mm): a wrong board size (--square-mm) is a likely cause, or the camera intrinsics, the robot's "
            "accuracy, or something that moved";
    return text.str();
  }
  return "";
}

}  // namespace binpick::calibration::detail
