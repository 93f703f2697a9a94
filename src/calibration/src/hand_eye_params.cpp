// HandEyeParams::validate.
#include <cmath>

#include "binpick/calibration/hand_eye.hpp"
#include "binpick/io/error.hpp"

namespace binpick::calibration {
namespace {

void require(bool ok, const char* field, const char* rule, double value) {
  requireField(ok, "HandEyeParams", field, rule, value);
}

bool positive(double v) { return std::isfinite(v) && v > 0.0; }
bool nonNegative(double v) { return std::isfinite(v) && v >= 0.0; }

}  // namespace

void HandEyeParams::validate() const {
  // OpenCV's solvers need 3 views; fewer than 4 leave no residual to judge a view by.
  require(min_views >= 4, "min_views", ">= 4", min_views);
  require(nonNegative(min_rotation_deg) && min_rotation_deg < 180.0, "min_rotation_deg",
          "in [0, 180)", min_rotation_deg);
  require(nonNegative(min_axis_spread_deg) && min_axis_spread_deg < 180.0, "min_axis_spread_deg",
          "in [0, 180)", min_axis_spread_deg);
  require(std::isfinite(inverted_fit_ratio) && inverted_fit_ratio > 1.0, "inverted_fit_ratio",
          "> 1", inverted_fit_ratio);
  require(std::isfinite(outlier_factor) && outlier_factor > 1.0, "outlier_factor", "> 1",
          outlier_factor);
  require(nonNegative(outlier_floor_mm), "outlier_floor_mm", ">= 0", outlier_floor_mm);
  require(nonNegative(outlier_floor_deg), "outlier_floor_deg", ">= 0", outlier_floor_deg);
  require(positive(max_rms_mm), "max_rms_mm", "positive", max_rms_mm);
  require(positive(max_rms_deg), "max_rms_deg", "positive", max_rms_deg);
}

}  // namespace binpick::calibration
