#pragma once
// Whether a calibration fits a capture. Where both the projector column and row decoded, a camera
// pixel names one projector ray; under the right calibration that ray meets the pixel's camera
// ray. How far they miss each other says how well the calibration (and the decoding's scale:
// a pattern set coded at a fraction of the projector's resolution) fits the capture, long before
// the cloud looks wrong: a rig whose Gray codes cover 2 x 2 projector pixels decoded as if they
// covered one gives rays missing by hundreds of millimetres, decoded right by about two.
//
// Two measures per pixel, both with the lens distortion of both devices removed as triangulation
// removes it (triangulation_tables.hpp):
// * the distance of the decoded (column, row) from the pixel's epipolar line, in projector
//   pixels (what TriangulationParams::max_epipolar_error limits), measured in the undistorted
//   projector image;
// * the gap between the two rays where they pass closest, in millimetres: the error in space at
//   the depth the point is triangulated at. Pixels whose rays pass closest behind either device,
//   or that are parallel, have no gap.
// Stateless: thread-safe.
#include "binpick/io/rig_calibration.hpp"
#include "binpick/reconstruction/decoder.hpp"
#include "binpick/reconstruction/triangulation.hpp"

namespace binpick::reconstruction {

// Every pixel measured (a Triangulator samples every 4th). Uses params.max_epipolar_error,
// params.max_calibration_residual and params.threads. Throws core::Error on an invalid rig or
// params, or when `decoded` is not the camera's image size.
CalibrationFit measureCalibrationFit(const io::RigCalibration& rig, const DecodedCapture& decoded,
                                     const TriangulationParams& params = {});

}  // namespace binpick::reconstruction
