#pragma once
// Grasps generated from the part model instead of written by hand: where a suction cup seals on
// the part, or where parallel jaws hold it between two opposite faces. Grasps are in the model
// frame (picking.hpp's Grasp and grasp-frame convention, gripper.hpp's gripper geometry), one per
// equivalence class under the part's symmetry, ranked best first. Stateless functions: thread-safe.
//
// How:
// - The surface is sampled (area-uniform, seeded, thinned to sample_spacing); every sample is a
//   candidate grasp point, its outward normal n the reverse of the approach (z = -n).
// - Suction: rays cast along the approach through the cup disc (the rim and half the radius)
//   must all meet the surface within (1 - seal_reserve) x gripper.seal_tolerance of the disc's
//   plane, on surface facing the cup, with nothing closer above it: the disc lies on one planar or
//   gently curved patch, no edge or gap inside it. On a cylinder or cone that is the sag of the
//   cup's rim: a 6 mm cup holds a shaft 16 mm across or more, not one of 15. Nothing of the part
//   may rise above the disc's plane within cup_clearance around it (a groove just wider than the
//   cup), and the cup and the tool body behind it must keep tool_clearance from the part.
// - Parallel jaw: a ray into the part from the sample leaves it through an opposite face (normals
//   opposite within max_antipodal_angle_deg) no wider than gripper.stroke; the jaws close along n.
//   The far face is where the ray first leaves the part (a wall held across its thickness) or
//   where it leaves it last (the part held across its whole extent, a ring across its diameter).
//   For approach_directions turns about n, both finger contact rectangles (finger_width x
//   finger_depth) must lie on their faces (within contact_tolerance) over at least half their
//   area, or touch them along a line at least half the finger's width long (a shaft, a rim), and
//   the fingers (with their path along the approach) and the tool body must be free. The contact
//   is taken 2 mm from the fingertips where it holds there, else at the fingers' middle.
// - Quality in [0, 1]: margin_weight x the seal margin (suction: how far the disc can grow and
//   still seal, up to twice its radius; parallel: how much of the finger rectangles touch), plus
//   the rest x closeness to the centre of mass (less torque when lifted).
// - Selection: best first; a grasp within min_separation (and symmetry_angle_deg) of a kept one,
//   after any symmetry of the part, is the same grasp. Every face (smooth patch of the surface)
//   gets its best grasp before any face gets a second, up to max_grasps.
// Names read "suction 3 (face +z)" or "parallel 2 (faces +-x, 30.0 mm)": the rank, and the face's
// outward normal as a model axis when it is within 10 degrees of one.
#include <cstdint>
#include <vector>

#include "binpick/io/point_cloud.hpp"
#include "binpick/picking/gripper.hpp"
#include "binpick/picking/picking.hpp"

namespace binpick::picking {

struct GraspGenerationParams {
  double sample_spacing = 0.003;         // metres between candidate grasp points on the surface
  int max_samples = 6000;                // candidate points at most (the spacing grows to fit)
  std::uint32_t seed = 1;                // surface sampling
  int max_grasps = 40;                   // grasps returned at most, >= 1
  double min_separation = 0.010;         // metres: closer grasps (after symmetry) are one grasp
  double symmetry_angle_deg = 10.0;      // approach (and closing axis) difference for "the same"
  double max_antipodal_angle_deg = 5.0;  // parallel: opposite faces' normals, degrees from opposite
  double contact_tolerance = 0.001;      // metres: a finger's contact surface may leave its plane
  int approach_directions = 8;           // parallel: approaches tried about the closing axis
  double margin_weight = 0.6;            // quality = w x margin + (1 - w) x closeness to the centre
  // Suction: the share of the cup's seal tolerance a grasp leaves unused, for what the model does
  // not show at the pick: the pose's error, the turn the planner gives a grasp about a revolved
  // axis (off the facets of the mesh it was found on). A 6 mm cup sagging 0.68 mm on a 14 mm
  // shaft (0.8 mm tolerance) seals on the model and failed 57 of 146 picks so placed (5 bins).
  double seal_reserve = 0.25;  // in [0, 1)
  // Suction: metres of room the cup keeps from the part's own walls around it, for the same
  // reasons. A 6 mm cup fits the gear's 6.5 mm tooth gap with 0.25 mm each side: it sealed there
  // on the model and failed 4 of 9 picks so placed, across the gap's edge (5 bins).
  double cup_clearance = 0.001;  // >= 0
  // Suction: metres by which the cup and the tool body, behind the sealed face, keep clear of the
  // rest of the part. The planner grows the tool by picking's collision_margin (2 mm) against the
  // measured cloud, and the part's own surface is in that cloud: a grasp closer than that to a
  // wall of its own part is refused wherever that wall is seen. The flanged hub's grasp on its
  // hub sat with the cup 1 mm from the flange: refused against the flange's rim at every pick.
  double tool_clearance = 0.003;  // >= 0; keep above collision_margin
  void validate() const;          // throws core::Error naming the field
};

// Grasps on a closed mesh (metres, outward normals: counter-clockwise seen from outside). Empty
// when the gripper fits nowhere. Deterministic for params.seed. Throws core::Error naming the
// field or the mesh when params, gripper or mesh are invalid.
std::vector<Grasp> generateGrasps(const io::TriangleMesh& model, const GripperParams& gripper,
                                  const PartSymmetry& symmetry, const GraspGenerationParams& params);

// The same on a model given as a cloud with outward unit normals: every point stands for a small
// disc of the surface (radius 1.5 x its typical neighbour distance), so the cloud must cover the
// surface densely and evenly. Throws when the cloud has no normals.
std::vector<Grasp> generateGrasps(const io::PointCloud& model, const GripperParams& gripper,
                                  const PartSymmetry& symmetry, const GraspGenerationParams& params);

}  // namespace binpick::picking
