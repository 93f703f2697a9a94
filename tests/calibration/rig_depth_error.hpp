#pragma once
// Test support: how far a recovered rig calibration puts depth from where the true rig does. A
// plane facing the camera at each given distance is "decoded" exactly under the true rig (every
// camera pixel gets the projector column and row the truth maps it to) and triangulated with the
// recovered rig, as `binpick reconstruct` would: the error is |z recovered - z true|, pooled over
// the planes' pixels lit by the projector.
#include <vector>

#include "binpick/io/rig_calibration.hpp"

namespace binpick::test {

// Median |dz| in millimetres over a grid of camera pixels (every `step` pixels) on planes at
// `distances` (metres, camera z).
double medianDepthErrorMm(const io::RigCalibration& recovered, const io::RigCalibration& truth,
                          const std::vector<double>& distances = {0.75, 0.9, 1.05}, int step = 8);

}  // namespace binpick::test
