#pragma once
// Internal: the mixed pixels of a view. A camera pixel gathers light over its area and its lens blur;
// one that straddles a depth edge sees two surfaces at once, and under every pattern its value is
// a blend of theirs. The ray through its centre sees only one of them: such pixels are found from
// the one-ray geometry and traced again with several rays over what they gather. Pure: thread-safe.
#include "binpick/io/rig_calibration.hpp"
#include "binpick/simulation/pattern_renderer.hpp"
#include "binpick/simulation/ray_caster.hpp"
#include "binpick/simulation/sensor_geometry.hpp"
#include "sensor/pixel_lighting.hpp"

namespace binpick::simulation::detail {

// The mixed pixels of `geometry` (computeSensorGeometry of `rig` in `scene`). Candidates are the
// pixels with an 8-neighbour that sees another object, nothing where they see something, or a
// depth more than 8 pixel footprints away, and those within the lens blur's reach of them
// (photometry.camera_blur_sigma). Each is traced again with k x k rays, k =
// photometry.mixed_pixel_samples, placed at equal shares of what the pixel gathers (its area
// seen through the blur); rays that see the same object, lit alike and at depths within an edge
// step, are one surface, whose light is their mean (their spread over the projector image added
// to its blur) and whose share is theirs. A candidate that sees one surface with all its rays is
// not mixed and is left out. None when k is 1.
MixedPixels computeMixedPixels(const io::RigCalibration& rig, const RayCaster& scene, const SensorGeometry& geometry,
                               const PhotometryParams& photometry, const AlbedoFunction& albedo,
                               const SensorGeometryParams& geometry_params);

}  // namespace binpick::simulation::detail
