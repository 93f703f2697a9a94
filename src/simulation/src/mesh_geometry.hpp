#pragma once
// Geometric measures of closed triangle meshes used to build parts and piles.
// Internal to binpick::simulation. Pure functions: thread-safe.
#include <Eigen/Geometry>
#include <vector>

#include "binpick/io/point_cloud.hpp"

namespace binpick::simulation::detail {

// Signed volume (positive for a closed mesh with outward normals) and its centroid, from the
// tetrahedra spanned by each triangle and the origin.
double signedVolume(const io::TriangleMesh& mesh);
Eigen::Vector3d volumeCentroid(const io::TriangleMesh& mesh);

// The same mesh with every vertex moved by `offset`.
io::TriangleMesh translated(const io::TriangleMesh& mesh, const Eigen::Vector3d& offset);

// Appends the closed axis-aligned box [lo, hi] with outward-facing triangles (12, two per face;
// the first face is z = lo).
void appendBox(io::TriangleMesh& mesh, const Eigen::Vector3f& lo, const Eigen::Vector3f& hi);

// Points on the surface such that every surface point lies within `coverage_radius` of one of
// them; includes every vertex. About 1.25 / coverage_radius^2 points per unit area.
std::vector<Eigen::Vector3f> surfaceSamples(const io::TriangleMesh& mesh, double coverage_radius);

}  // namespace binpick::simulation::detail
