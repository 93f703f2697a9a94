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
// The approach corridor is the cylinder of radius tool_radius + wall_clearance around the segment
// from the pre-grasp to the grasp point. It hits a wall when a slice of it reaching below the wall
// top has its axis outside the bin's inner box shrunk by that radius (checked analytically: exact
// for a vertical approach, on the safe side for a tilted one). It hits the floor when its axis
// goes below the floor: the grasp point itself may lie just above it (a flat part lying on the
// floor), so neither the radius nor the clearance applies there.
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

namespace binpick::cell {

struct Grasp {
  std::string name;
  Eigen::Isometry3d T_model_grasp = Eigen::Isometry3d::Identity();  // metres
};

// Rotations mapping the part onto itself about its model origin: a grasp S * T_model_grasp is as
// good as T_model_grasp. With a continuous axis too, every discrete S is combined with
// continuous_symmetry_steps even rotations about the axis.
struct PartSymmetry {
  // Proper rotations; must hold the identity (so the grasp as taught is always a candidate).
  std::vector<Eigen::Matrix3d> discrete{Eigen::Matrix3d::Identity()};
  std::optional<Eigen::Vector3d> continuous_axis;  // axis through the origin (normalised here)
};

// The bin's inside: a box on its floor. Bin frame: origin at the centre of the floor, x along
// `length`, y along `width`, z up.
struct BinBox {
  Eigen::Isometry3d T_base_bin = Eigen::Isometry3d::Identity();  // rigid, metres
  double length = 0.40, width = 0.30, wall_height = 0.15;  // metres, inner sizes
};

enum class PickOrder { HighestFirst, BestScore };
PickOrder pickOrderFromName(const std::string& name);  // "highest_first" | "best_score"

struct PickParams {
  std::vector<Grasp> grasps;               // at least one; rigid, finite poses
  PartSymmetry symmetry;
  BinBox bin;
  double approach_distance = 0.10;         // metres from pre-grasp to grasp point
  double tool_radius = 0.025;              // metres: the approach corridor's radius
  double wall_clearance = 0.005;           // metres kept between the corridor and the walls
  double max_tilt_deg = 60.0;              // approach vs straight down (base -z); steeper: rejected
  int continuous_symmetry_steps = 36;      // grasps tried around a continuous axis, in [1, 3600]
  // HighestFirst: the grasp point's base z, descending; BestScore: detection score, descending.
  // Ties: the other key, then the object index.
  PickOrder order = PickOrder::HighestFirst;
  double avoid_radius = 0.02;              // metres: a failed object's centre this close is avoided
  void validate() const;                   // throws binpick::Error naming the field
};

struct DetectedPart {
  Eigen::Isometry3d T_base_model = Eigen::Isometry3d::Identity();
  double score = 0.0;  // detection score, higher is better
};

struct Pick {
  int object = 0;   // index into the detections
  int grasp = 0;    // index into PickParams::grasps
  Eigen::Isometry3d T_base_grasp = Eigen::Isometry3d::Identity();
  double tilt_deg = 0.0;  // approach vs straight down
};

struct PickPlan {
  std::vector<Pick> picks;  // in pick order, at most one per object
  int rejected_collision = 0;  // objects whose every grasp hits the bin (or exceeds max_tilt)
  int rejected_avoided = 0;    // objects near a failed pick
  int rejected_invalid = 0;    // objects with a non-finite or non-rigid pose, or non-finite score
};

// `avoid` holds the base-frame centres (T_base_model translations) of objects the robot failed
// to pick; non-finite entries avoid nothing. Of a part's surviving candidates the least tilted is
// picked; within 1e-6 degrees of it, the lowest grasp index, then the one whose tool x axis lies
// closest to base +x (projected normal to the approach): symmetric parts get a canonical wrist
// angle. Throws binpick::Error when params.validate() does.
PickPlan planPicks(const std::vector<DetectedPart>& parts,
                   const std::vector<Eigen::Vector3d>& avoid, const PickParams& params);

}  // namespace binpick::cell
