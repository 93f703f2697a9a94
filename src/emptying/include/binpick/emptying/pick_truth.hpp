#pragma once
// Would the robot really hold a part? The virtual cell's judge of a commanded pick: the gripper
// (cell/gripper.hpp) at the commanded grasp pose, against the TRUE scene (the parts where the
// physics put them, and the bin), whatever the detection believed. Everything in the bin frame
// (origin at the centre of the floor's top face, z up), metres.
//
// Suction: the cup's centre lies on a part's surface (within surface_tolerance along the axis), the
// approach is within max_axis_angle_deg of that surface's inward normal, the whole cup disc lies
// on that part's face (rays along the approach through rings of samples over the disc hit the same
// part within the gripper's seal_tolerance of the face's plane at the centre: the bellows takes up
// the tilt, not steps, gaps or neighbours), and the cup and the tool body, swept back along the
// approach by approach_distance, meet no surface of any part or of the bin.
// Parallel jaws: with the jaws open (to the stroke, or to the opening the cell commands), the
// fingers and the body sweep in without collision; closing, each jaw's face first meets the same
// part, on faces whose normals are opposite within max_antipodal_angle_deg.
// A pick that passes is held by the part under the cup (or between the jaws), whichever part that
// is: a pick aimed at one part that seals on its neighbour lifts the neighbour.
//
// Ray sampling has a resolution: a gap narrower than sample_spacing under the cup, or an obstacle
// thinner than collision_spacing in the tool's path, may pass unseen.
#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "binpick/io/point_cloud.hpp"
#include "binpick/picking/gripper.hpp"
#include "binpick/simulation/physics_pile.hpp"
#include "binpick/simulation/ray_caster.hpp"

namespace binpick::emptying {

struct PickTruthParams {
  double surface_tolerance = 0.002;       // metres: the cup centre's distance to the surface, along the axis
  double max_axis_angle_deg = 10.0;       // approach against the surface's inward normal under the cup
  double max_antipodal_angle_deg = 20.0;  // parallel: the two contact normals from opposite
  double sample_spacing = 0.001;          // metres between rays over the cup disc and the finger faces
  double collision_spacing = 0.002;       // metres between rays through the tool's cross-section
  void validate() const;                  // throws core::Error naming the field
};

// The judge's verdict. `reason` is empty when ok, otherwise one of these short phrases (N a
// number), stable so that reports can count them:
//   suction:  "off the part", "cup on the bin", "tilted N deg from the surface",
//             "cup across an edge", "cup over a gap", "cup on a neighbour",
//   parallel: "part wider than the stroke", "nothing between the jaws", "jaw on the bin",
//             "jaws on two parts", "jaw faces N deg from opposite",
//   both:     "tool hits part N", "tool hits the bin", and for the jaws "finger hits part N",
//             "finger hits the bin".
struct PickJudgement {
  static constexpr int kBin = -2;  // `obstacle` when the bin is in the way

  bool ok = false;
  std::string reason;
  int object = -1;    // the part held (index into the T_bin_objects list), or -1
  int touched = -1;   // the part under the cup or first met by a jaw, held or not; -1 for none
  int obstacle = -1;  // what the tool or a finger hits: a part's index, kBin, or -1
  // Suction: from the cup's centre to the surface along the approach, metres (positive: the
  // surface lies ahead of the cup). Parallel: the width between the two contacts, metres.
  double distance = std::numeric_limits<double>::quiet_NaN();
  // Suction: the approach against the surface's inward normal. Parallel: how far the contact
  // normals are from opposite. Degrees.
  double angle_deg = std::numeric_limits<double>::quiet_NaN();
};

// The true scene in the bin frame: the parts at their poses and the bin's mesh, ready for rays.
// Immutable once built: judgePick may run on it from any number of threads at once.
class TrueScene {
 public:
  // Throws core::Error on an empty or malformed part mesh, a pose that is not a finite rigid
  // transform, or a bad bin.
  TrueScene(const io::TriangleMesh& part, const std::vector<Eigen::Isometry3d>& T_bin_objects,
            const simulation::BinInterior& bin);

  int parts() const { return parts_; }
  // Parts have ids 0 .. parts() - 1 (their index), the bin PickJudgement::kBin.
  const simulation::RayCaster& caster() const { return caster_; }

 private:
  int parts_ = 0;
  simulation::RayCaster caster_;
};

// Judges the gripper at T_bin_grasp (grasp frame: gripper.hpp) reaching it along its z axis from
// approach_distance behind. Parallel jaws open to `opening` (metres between the contact faces, at
// most the stroke; <= 0: the stroke), as a cell opens them to the part's width and a margin so as
// not to reach into the neighbours. Expected failures are values (ok false, a reason); throws
// core::Error only on bad input: invalid params or gripper, a negative or non-finite
// approach_distance, a grasp pose that is not a finite rigid transform.
PickJudgement judgePick(const TrueScene& scene, const Eigen::Isometry3d& T_bin_grasp,
                        const picking::GripperParams& gripper, double approach_distance, const PickTruthParams& params,
                        double opening = 0.0);

}  // namespace binpick::emptying
