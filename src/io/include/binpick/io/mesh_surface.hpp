#pragma once
// A mesh's surface as points: its area and seeded samples spread over it in proportion to area,
// each with its face's normal. Used by model preparation (estimation) and the symmetry search
// (mesh_symmetry.hpp). Stateless: thread-safe.
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "binpick/io/point_cloud.hpp"

namespace binpick::io {

struct SurfaceSamples {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> face_normals;  // unit, outward for counter-clockwise triangles
};

// `count` samples (fewer when degenerate faces are drawn); none for a mesh without area.
SurfaceSamples sampleSurface(const TriangleMesh& mesh, std::size_t count, uint64_t seed);
double surfaceArea(const TriangleMesh& mesh);

}  // namespace binpick::io
