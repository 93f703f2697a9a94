#pragma once
// Procedural industrial parts: closed triangle meshes in metres, outward normals, model frame at
// the volume centroid (axes: those of the profile's drawing, the extrusion along z), with their
// symmetry declared for scoring. Stateless: thread-safe.
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "binpick/io/mesh_symmetry.hpp"
#include "binpick/io/point_cloud.hpp"

namespace binpick::simulation {

// The rotations that map a part onto itself (about its model origin): declared by hand for the
// built-in parts (io::findSymmetry finds the same), found from the mesh for a user's.
using Symmetry = io::Symmetry;

struct Part {
  std::string name;
  std::string description;
  io::TriangleMesh mesh;
  Symmetry symmetry;
};

// Names of the built-in parts, e.g. "l_bracket", "clamp".
std::vector<std::string> partNames();
// Builds a built-in part; throws core::Error naming the unknown part.
Part makePart(const std::string& name);
// A user's mesh as a part (as it is: not re-centred), its symmetry found from the mesh
// (io::findSymmetry) and named in its description.
Part partFromMesh(const std::string& name, io::TriangleMesh mesh);

// A prism: a simple polygon (counter-clockwise, metres, in the xy plane) extruded along z by
// `thickness`, centred on z = 0. Throws on a degenerate or self-intersecting profile.
// The profile keeps its coordinates (x, y are not re-centred). A clockwise profile is reversed,
// and repeated or collinear points are dropped, so the mesh is always closed with outward normals.
io::TriangleMesh makePrism(const std::vector<Eigen::Vector2d>& profile, double thickness);

// A lathe (surface of revolution): a simple polygon in the (r, z) half-plane (r >= 0; either
// orientation; repeated or collinear points are dropped) revolved about the z axis with `segments`
// facets (>= 3), the first at angle 0 (on +x). Profile points on the axis (r = 0) become a single
// vertex each (no degenerate triangles), and a profile edge lying on the axis bounds no surface.
// The mesh is closed with outward normals and keeps the profile's z (no re-centring). Throws on a
// point with r < 0, a degenerate or self-intersecting profile, or too few segments.
io::TriangleMesh makeLathe(const std::vector<Eigen::Vector2d>& profile, int segments);

// Rotation + translation error between an estimate and the truth, minimised over the symmetry:
// the estimate is compared with every truth * S (S a symmetry rotation, in the model frame), and
// with a continuous axis a only the angle between R_est a and R_true S a counts. The translation
// error is the distance between the model origins (symmetries fix the origin).
struct PoseError {
  double translation = 0.0;  // metres (or the mesh's unit)
  double rotation_deg = 0.0;
};
PoseError poseError(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth, const Symmetry& symmetry);

}  // namespace binpick::simulation
