#pragma once
// The rotations that map a part onto itself about its model origin, found from its mesh: turns
// about one axis (N-fold, or any angle for a revolved part) and the half-turns about the axes
// perpendicular to it (a part that looks the same flipped over). Faceted CAD counts: a polygonal
// cylinder is revolved when its facets stray from the circle by less than the tolerance. The one
// place a symmetry is found: picking's grasps and planner, the virtual cell's scoring and the
// cell's recipes use it wherever no symmetry is given. Stateless: thread-safe.
//
// Method: the candidate axes are the principal axes of the surface's second moments (exact, from
// the triangles; a symmetry axis is one of them). A rotation is a symmetry when every probe point
// (samples spread over the surface by area), turned, lies within the tolerance of the surface.
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "binpick/io/point_cloud.hpp"

namespace binpick::io {

// Rotations mapping a part onto itself about its model origin.
struct Symmetry {
  std::vector<Eigen::Matrix3d> discrete{Eigen::Matrix3d::Identity()};  // proper rotations, the identity first
  std::optional<Eigen::Vector3d> continuous_axis;                      // unit axis through the origin, if any
};

struct SymmetryParams {
  // A rotation maps the part onto itself when every turned probe lies within this share of the
  // part's size (its bounding box's diagonal) of the surface: faceting and CAD tolerances.
  double tolerance = 0.005;
  int max_order = 60;     // the highest N tried; a part of more turns than this counts as revolved
  int probes = 2000;      // surface points turned
  uint64_t seed = 1;      // of the probes' placement
  void validate() const;  // throws core::Error naming the field
};

struct FoundSymmetry {
  Symmetry symmetry;
  // The axis the part turns about (unit, model frame), zero when it has none; `turns` is N of an
  // N-fold axis, 0 for a revolved part, 1 for none.
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();
  int turns = 1;
  bool flips = false;  // half-turns about axes perpendicular to `axis` map it onto itself too
  // "revolved about (0, 0, 1), flips over", "12-fold about (0, 0, 1), flips over: 24 rotations",
  // "none"; with why, when the origin keeps a symmetry about the centroid out.
  std::string description;
};

// Throws core::Error on an empty or invalid mesh or bad params.
FoundSymmetry findSymmetry(const TriangleMesh& mesh, const SymmetryParams& params = {});

// "any turn about (0, 0, 1) with 2 rotations" / "24 rotations" / "none": what a given symmetry holds.
std::string describeSymmetry(const Symmetry& symmetry);

}  // namespace binpick::io
