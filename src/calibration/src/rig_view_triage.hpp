#pragma once
// Which views a rig calibration can use, and what to tell the user about each of the others.
#include <string>
#include <vector>

#include "binpick/calibration/rig_calibrator.hpp"

namespace binpick::calibration::detail {

// Why `view` cannot be used ("board not found: ...", "only 6 corners ..."); empty when usable.
std::string viewProblem(const RigView& view, const RigCalibrationParams& params);

// Warnings about a usable view that lost corners: the board partly outside the camera image (or
// hidden), or corners without a projector pixel (outside the projector's light, poorly decoded).
std::vector<std::string> viewWarnings(const RigView& view);

// Throws core::Error unless every usable view has the first one's camera and projector size.
void requireSameSizes(const std::vector<RigView>& views, const std::vector<std::size_t>& usable);

// The error for too few usable views: how many, and every unusable view with its problem.
std::string tooFewViewsMessage(const std::vector<RigView>& views, const std::vector<std::string>& problems, int usable,
                               int min_views);

}  // namespace binpick::calibration::detail
