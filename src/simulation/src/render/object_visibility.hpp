#pragma once
// Per-object visibility for ground truth: how much of each object the rig can measure in the
// pile, against how much it could measure were the object alone (BOP's visib_fract, with the
// projector's light and shadows added: a structured-light sensor measures only what is both seen
// and lit). Stateless: thread-safe.
#include <vector>

#include "binpick/io/rig_calibration.hpp"
#include "binpick/simulation/ray_caster.hpp"
#include "binpick/simulation/sensor_geometry.hpp"

namespace binpick::simulation {

struct ObjectVisibility {
  int visible_lit_pixels = 0;     // camera pixels seeing this object, lit, in the full scene
  int alone_lit_pixels = 0;       // the same were the object alone at its pose (self-shadow counts)
  double visible_fraction = 0.0;  // visible_lit_pixels / alone_lit_pixels; 0 when that is 0
};

// One entry per object of `scene`, in its order. `geometry` must come from
// computeSensorGeometry(rig, scene, ...) with the same params. Only the pixels inside each
// object's projected bounding box are examined, and of those only the ones where the object is
// hidden or shadowed in `geometry` are cast again, against the object alone. Throws
// core::Error on an invalid rig or params, or a geometry of the wrong size.
std::vector<ObjectVisibility> computeObjectVisibility(const io::RigCalibration& rig, const RayCaster& scene,
                                                      const SensorGeometry& geometry,
                                                      const SensorGeometryParams& params = {});

// The same for the objects listed (indices into `scene`), in that order: e.g. the parts but not
// the bin, whose bounding box covers much of the image. Throws core::Error on a bad index.
std::vector<ObjectVisibility> computeObjectVisibilityOf(const io::RigCalibration& rig, const RayCaster& scene,
                                                        const SensorGeometry& geometry,
                                                        const std::vector<int>& object_indices,
                                                        const SensorGeometryParams& params = {});

}  // namespace binpick::simulation
