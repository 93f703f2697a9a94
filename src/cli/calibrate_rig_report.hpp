#pragma once
// What `calibrate rig` prints: a table of the views (corners in both images, RMS in both, outlier,
// used or why not) and the calibration's totals and figures.
#include <ostream>

#include "binpick/calibration/rig_calibrator.hpp"

namespace binpick::cli {

void printRigReport(std::ostream& out, const calibration::RigCalibrationResult& result);

}  // namespace binpick::cli
