#pragma once
// From detected parts to the robot's picks: candidate grasps (defined in the model frame, several
// per part, repeated over the part's symmetries), grasps whose approach would hit the bin walls
// or floor rejected, objects the robot failed to pick avoided, one pick per part, ordered, in the
// robot base frame. Stateless functions: thread-safe.
//
// Frames: a grasp frame's z axis is the tool's approach direction (pointing into the part); the
// tool reaches the grasp point by moving along +z from the pre-grasp point, approach_distance
// back along -z.
//
// The approach corridor is the cylinder of radius gripper.tool_radius + wall_clearance around the segment
// from the end of the tool body at the pre-grasp point (gripper.toolBack() behind it) to the grasp
// point; a suction cup's own stretch, cup_length behind the grasp point, is only as wide as the cup
// (+ wall_clearance). It hits a wall when a slice of it reaching below the wall
// top has its axis outside the bin's inner box shrunk by that radius (checked analytically: exact
// for a vertical approach, on the safe side for a tilted one). It hits the floor when its axis
// goes below the floor: the grasp point itself may lie just above it (a flat part lying on the
// floor), so neither the radius nor the clearance applies there. A suction grasp whose corridor
// meets a wall is leaned away from it about the grasp point, by up to gripper.max_lean_deg
// (Pick::lean_deg); the seal is still judged on the face. A bent nose (gripper.bent()) is tried
// turned about the approach, its body most upright first; its body's corridor is the
// parallelogram its axis sweeps from the pre-grasp point, grown by the same radius.
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "binpick/io/mesh_symmetry.hpp"
#include "binpick/io/point_cloud.hpp"
#include "binpick/picking/gripper.hpp"
#include "binpick/picking/seal_check.hpp"

namespace binpick::picking {

struct Grasp {
  std::string name;
  Eigen::Isometry3d T_model_grasp = Eigen::Isometry3d::Identity();  // metres
  // How good the grasp is on the part alone, in [0, 1] (grasp_generation.hpp: seal margin, distance
  // from the centre of mass); hand-written grasps count as 1.
  double quality = 1.0;
  // Parallel jaw: the part's width between the two contact points, metres; the fingers open to
  // it plus PickParams::finger_clearance each side (at most the stroke). 0: unknown, fully open.
  double width = 0.0;
};

// Rotations mapping the part onto itself about its model origin: a grasp S * T_model_grasp is as
// good as T_model_grasp. With a continuous axis too, every discrete S is combined with
// continuous_symmetry_steps even rotations about the axis.
// Found from the part's mesh (io::findSymmetry) where a recipe gives none. The discrete
// rotations must hold the identity (so the grasp as taught is always a candidate); the
// continuous axis is normalised here.
using PartSymmetry = io::Symmetry;

// The bin's inside: a box on its floor. Bin frame: origin at the centre of the floor, x along
// `length`, y along `width`, z up.
struct BinBox {
  Eigen::Isometry3d T_base_bin = Eigen::Isometry3d::Identity();  // rigid, metres
  double length = 0.40, width = 0.30, wall_height = 0.15;        // metres, inner sizes
};

enum class PickOrder { HighestFirst, BestScore, BestRank };
// "highest_first" | "best_score" | "best_rank"
PickOrder pickOrderFromName(const std::string& name);

// The ranking value of a surviving grasp (Pick::rank), a weighted sum of terms near [0, 1], each
// "higher is likelier to succeed":
//   free       1 - the share of the measured columns within cover_radius of the grasp point that
//              rise more than cover_height above it (1 without a measured scene): the part on top
//   height     the grasp point's height above the bin floor / wall_height (not clamped)
//   coverage   DetectedPart::coverage: how much of the part the fit explains
//   upright    1 - tilt_deg / 90
//   clearance  Pick::clearance / clearance_cap (1 without a measured scene)
//   quality    Grasp::quality
// A part's pick is its best-ranked grasp; PickOrder::BestRank orders the parts by it, after the
// sure parts first: a pose the detector is not sure of may be its turned twin, and no rank term
// sees that.
struct RankWeights {
  double free = 2.0;  // being on top matters most: a buried part drags its neighbours along
  double height = 1.0;
  double coverage = 1.0;
  double upright = 1.0;
  double clearance = 0.5;
  double quality = 1.0;
  void validate() const;  // each finite and >= 0; throws core::Error naming the field
};

struct PickParams {
  std::vector<Grasp> grasps;  // at least one; rigid, finite poses
  PartSymmetry symmetry;
  BinBox bin;
  GripperParams gripper;               // the tool: its radius is the approach corridor's
  double approach_distance = 0.10;     // metres from pre-grasp to grasp point
  double wall_clearance = 0.005;       // metres kept between the corridor and the walls
  double max_tilt_deg = 60.0;          // approach vs straight down (base -z); steeper: rejected
  int continuous_symmetry_steps = 36;  // grasps tried around a continuous axis, in [1, 3600]
  // HighestFirst: the grasp point's base z, descending; BestScore: detection score, descending;
  // BestRank: the sure parts (DetectedPart::sure) first, each group by Pick::rank, descending.
  // Ties: height or score, then the object index.
  PickOrder order = PickOrder::BestRank;
  double avoid_radius = 0.02;  // metres: a failed object's centre this close is avoided
  // The tool against the measured cloud (tool_collision.hpp), when planPicks is given one:
  double collision_margin = 0.002;  // metres the tool's volume is grown by (cloud noise)
  double finger_clearance = 0.005;  // metres between an open finger and the part, each side
  double clearance_cap = 0.02;      // metres: clearances up to this count in the ranking
  double cover_radius = 0.04;       // metres around the grasp point searched for cover
  double cover_height = 0.005;      // metres above the grasp point a covering point rises
  RankWeights ranking;
  SealCheckParams seal_check;  // suction: the measured surface under the cup (seal_check.hpp)
  void validate() const;       // throws core::Error naming the field
  // Jaws open to the grasp's width plus finger_clearance each side; 0 when its width is unknown
  // (GripperParams::jawOpening then opens them fully).
  double jawOpeningFor(const Grasp& grasp) const {
    return grasp.width > 0.0 ? grasp.width + 2.0 * finger_clearance : 0.0;
  }
};

struct DetectedPart {
  Eigen::Isometry3d T_base_model = Eigen::Isometry3d::Identity();
  double score = 0.0;     // detection score, higher is better
  double coverage = 1.0;  // share of the model points the camera should see that the fit covers
  // The detector is sure of the pose (estimation::Detection::sure): no turned twin explains the
  // range nearly as well and the fit covers enough. PickOrder::BestRank picks these first.
  bool sure = true;
};

struct Pick {
  int object = 0;  // index into the detections
  int grasp = 0;   // index into PickParams::grasps
  Eigen::Isometry3d T_base_grasp = Eigen::Isometry3d::Identity();
  double tilt_deg = 0.0;   // approach vs straight down
  double lean_deg = 0.0;   // approach vs the face's normal: > 0 where a wall made it lean
  double clearance = 0.0;  // metres between the tool and the nearest measured point (capped)
  double rank = 0.0;       // the ranking value the picks were ordered by, higher first
};

// Why parts were not picked, one count per part: the furthest test any of its grasps reached
// (tilt, then bin, then cloud, then seal) and failed.
struct PickRejections {
  int invalid = 0;  // a non-finite or non-rigid pose, or a non-finite score or coverage
  int avoided = 0;  // near a failed pick
  int tilt = 0;     // every grasp tilted beyond max_tilt_deg
  int bin = 0;      // every grasp within the tilt limit: the tool hits the bin's walls or floor
  int cloud = 0;    // every grasp left: the tool hits the measured cloud (a neighbour, the part)
  int seal = 0;     // every grasp left: the measured surface under the cup would not seal
  int total() const { return invalid + avoided + tilt + bin + cloud + seal; }
};

struct PickPlan {
  std::vector<Pick> picks;  // in pick order, at most one per object
  PickRejections rejected;
};

// The measured cloud in the robot base frame, indexed for the tool's collision test. Built once
// per cycle; immutable afterwards, so thread-safe to query. (Defined in tool_collision.cpp.)
class MeasuredScene;

// `avoid` holds the base-frame centres (T_base_model translations) of objects the robot failed
// to pick; non-finite entries avoid nothing. `scene` (may be null: no cloud test) is the measured
// cloud the tool must not run into; `surface` (may be null: no seal test) the organized cloud a
// suction cup must seal on. Every grasp of every symmetric copy is tested (tilt, bin, cloud, seal)
// and the surviving ones ranked (see PickParams); a part's best survivor is its pick.
// Throws core::Error when params.validate() does.
PickPlan planPicks(const std::vector<DetectedPart>& parts, const std::vector<Eigen::Vector3d>& avoid,
                   const PickParams& params, const MeasuredScene* scene = nullptr,
                   const MeasuredSurface* surface = nullptr);

}  // namespace binpick::picking
