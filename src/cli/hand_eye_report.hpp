#pragma once
// What `binpick calibrate hand-eye` prints: a table of the views (corners, board-pose RMS,
// residuals), the result, and the warnings.
#include <iosfwd>
#include <vector>

#include "binpick/calibration/hand_eye.hpp"
#include "binpick/calibration/hand_eye_views.hpp"

namespace binpick::cli {

// One row per view; `result` adds the residuals (nullptr when the solve failed).
void printViewTable(std::ostream& out, const std::vector<calibration::MeasuredView>& views,
                    const calibration::HandEyeResult* result);
// The transforms and the residual RMS.
void printHandEyeResult(std::ostream& out, const calibration::HandEyeResult& result);
// "warning: ..." lines: views left out, partial boards, outliers.
void printHandEyeWarnings(std::ostream& out, const std::vector<calibration::MeasuredView>& views,
                          const calibration::HandEyeResult* result);

}  // namespace binpick::cli
