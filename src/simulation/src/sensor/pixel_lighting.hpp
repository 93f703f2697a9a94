#pragma once
// From what each camera pixel sees (SensorGeometry) to the pattern-independent light budget of the
// pixel (PixelLighting): Lambertian reflection of the projector and of ambient light, a Blinn-Phong
// highlight, indirect light, and the projector's defocus at the surface point. Stateless:
// thread-safe.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <vector>

#include "binpick/io/rig_calibration.hpp"
#include "binpick/simulation/pattern_renderer.hpp"
#include "binpick/simulation/sensor_geometry.hpp"

namespace binpick::simulation {

// Diffuse reflectance in [0, 1] of the surface of object `object_id` at a point of its own frame
// (a calibration board's print depends on the point; a part's paint does not).
using AlbedoFunction = std::function<float(int32_t object_id, const Eigen::Vector3f& object_point)>;

std::vector<PixelLighting> computePixelLighting(const SensorGeometry& geometry, const io::RigCalibration& rig,
                                                const PhotometryParams& params, const AlbedoFunction& albedo);

}  // namespace binpick::simulation
