#pragma once
// Internal: a pile as the rig sees it, shared by generatePile (truth and clouds) and
// renderPileImages (pattern images). Pure functions: thread-safe.
#include <vector>

#include "binpick/simulation/pile.hpp"
#include "binpick/simulation/ray_caster.hpp"
#include "binpick/simulation/sensor_geometry.hpp"
#include "sensor/pixel_lighting.hpp"

namespace binpick::simulation::detail {

constexpr int32_t kBinId = -2;

// The parts (ids 0 .. n-1, in the order of `T_camera_object`) and the bin (kBinId), camera frame.
// `bin` must outlive the result.
std::vector<RenderObject> pileObjects(const io::TriangleMesh& part, const io::TriangleMesh& bin,
                                      const std::vector<Eigen::Isometry3d>& T_camera_object,
                                      const Eigen::Isometry3d& T_camera_bin);

// Every surface point the camera sees, lit or not, with its outward normal; NaN elsewhere.
io::PointCloud exactCloud(const SensorGeometry& geometry);

// What an ideal structured-light sensor measures: the points both seen and lit by the projector,
// and seen less obliquely than `max_view_angle_deg` (beyond it the pattern's stripes are too
// foreshortened to decode); NaN elsewhere. No normals.
io::PointCloud measurableCloud(const SensorGeometry& geometry, double max_view_angle_deg);

// Paint of the parts and the bin (PileParams) as an AlbedoFunction.
AlbedoFunction pileAlbedo(const PileParams& params);

}  // namespace binpick::simulation::detail
