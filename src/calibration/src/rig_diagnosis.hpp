#pragma once
// What a rig calibration's views pin poorly, from the own solves' standard deviations: the
// warnings for fewer views than recommended and for poses too alike to pin the principal points.
#include <string>
#include <vector>

#include "binpick/calibration/rig_calibrator.hpp"

namespace binpick::calibration::detail {

// Whether a device's principal point is poorly pinned: the standard deviation of cx or cy above
// params.max_principal_point_sd of the image's width.
bool principalPointPoorlyPinned(const LensFitReport& fit, int image_width, const RigCalibrationParams& params);

// "camera cx +- 20.3 px, cy +- 21.0 px, k2 -0.031 +- 1.454; projector ...": the intrinsics whose
// standard deviation exceeds the limits of RigCalibrationParams; empty when none does.
std::string poorlyDetermined(const RigCalibrationResult& result, const RigCalibrationParams& params);

// The board's width in the camera image (the extent of its corners along the image's x), as a
// share of the image's width, averaged over the views `used`.
double meanBoardSpan(const std::vector<RigView>& views, const std::vector<std::size_t>& used);

// The warnings: fewer usable views than params.recommended_views (naming what is poorly
// determined), and principal points poorly pinned (with how far apart the board's tilts are, how
// much of the image it fills, how far the stereo step moved them, and the remedy).
std::vector<std::string> geometryWarnings(const RigCalibrationResult& result, int views_used, double board_span,
                                          const RigCalibrationParams& params);

}  // namespace binpick::calibration::detail
