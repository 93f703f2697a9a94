// The parallel jaws' judge: a clear way in with the jaws open, then both jaws closing on opposite
// faces of one part.
#include <algorithm>
#include <cmath>
#include <limits>

#include "pick_rays.hpp"

namespace binpick::emptying::detail {
namespace {

// What a jaw meets first as it closes from its open position, `opening` / 2 off the grasp axis.
struct JawContact {
  bool hit = false;  // within the opening
  bool any = false;  // at any distance: even beyond the opening, a surface met from behind
  int object = -1;
  double travel = 0.0;       // metres from the open position
  Eigen::Vector3d normal;    // grasp frame, outward from the surface met
  bool from_inside = false;  // the jaw's open face already lay inside that solid
};

// side +1: the jaw at +x closing along -x; -1: the one at -x closing along +x.
JawContact closeJaw(const TrueScene& scene, const Eigen::Isometry3d& T_bin_grasp, const picking::GripperParams& gripper,
                    double opening, const PickTruthParams& params, int side) {
  const double half_width = 0.5 * gripper.finger_width, half_depth = 0.5 * gripper.finger_depth;
  std::vector<Eigen::Vector3d> origins;
  for (const Eigen::Vector2d& yz :
       rectangleSamples(-half_width, half_width, -half_depth, half_depth, params.sample_spacing)) {
    origins.emplace_back(side * 0.5 * opening, yz.x(), yz.y());
  }
  const Eigen::Vector3d closing(-side, 0.0, 0.0);
  // Traced past the opening: a face inside a part wider than the opening meets it from behind only
  // beyond the other jaw.
  JawContact first;
  for (const simulation::RayHit& hit :
       castFrom(scene, T_bin_grasp, origins, closing, std::numeric_limits<double>::infinity())) {
    if (!hit.hit() || (first.any && hit.t >= first.travel)) continue;
    first.any = true;
    first.object = hit.object_id;
    first.travel = hit.t;
    first.normal = T_bin_grasp.linear().transpose() * hit.normal;
    first.from_inside = first.normal.dot(closing) > 0.0;
  }
  first.hit = first.any && first.travel <= opening;
  return first;
}

// The open fingers (boxes outside the contact faces, up to their tips) swept back along the
// approach.
std::vector<Column> fingerColumns(const picking::GripperParams& gripper, double opening, double approach_distance,
                                  const PickTruthParams& params) {
  const double inner = 0.5 * opening, outer = inner + gripper.finger_thickness;
  const double half_width = 0.5 * gripper.finger_width, half_depth = 0.5 * gripper.finger_depth;
  std::vector<Column> columns;
  for (const double side : {1.0, -1.0}) {
    const double x0 = side > 0 ? inner : -outer, x1 = side > 0 ? outer : -inner;
    for (const Eigen::Vector2d& xy : rectangleSamples(x0, x1, -half_width, half_width, params.collision_spacing)) {
      columns.push_back({xy, -half_depth - approach_distance, half_depth});
    }
  }
  return columns;
}

std::vector<Column> bodyColumns(const picking::GripperParams& gripper, double approach_distance,
                                const PickTruthParams& params) {
  const double front = -0.5 * gripper.finger_depth;
  std::vector<Column> columns;
  if (gripper.tool_radius <= 0.0) return columns;
  for (const Eigen::Vector2d& xy : discSamples(gripper.tool_radius, params.collision_spacing)) {
    columns.push_back({xy, front - gripper.tool_length - approach_distance, front});
  }
  return columns;
}

// Empty when the two contacts grip one part from opposite sides.
std::string gripProblem(const JawContact& right, const JawContact& left, const std::string& wider) {
  if (!right.hit || !left.hit) return "nothing between the jaws";
  if (right.object == PickJudgement::kBin || left.object == PickJudgement::kBin) {
    return "jaw on the bin";
  }
  if (right.from_inside || left.from_inside) return wider;
  if (right.object != left.object) return "jaws on two parts";
  return {};
}

}  // namespace

PickJudgement judgeParallel(const TrueScene& scene, const Eigen::Isometry3d& T_bin_grasp,
                            const picking::GripperParams& gripper, double approach_distance, double opening,
                            const PickTruthParams& params) {
  PickJudgement judgement;
  opening = gripper.jawOpening(opening);
  const std::string wider = opening < gripper.stroke ? "part wider than the opening" : "part wider than the stroke";
  const JawContact right = closeJaw(scene, T_bin_grasp, gripper, opening, params, +1);
  const JawContact left = closeJaw(scene, T_bin_grasp, gripper, opening, params, -1);
  if (right.hit && right.object >= 0) judgement.touched = right.object;
  // Both open jaws inside one part: it is wider than they open (their sweep would hit it too,
  // but this says why).
  if (right.from_inside && left.from_inside && right.object == left.object && right.object >= 0) {
    judgement.touched = right.object;
    judgement.reason = wider;
    return judgement;
  }
  for (const auto& [solid, columns] : {std::pair{"finger", fingerColumns(gripper, opening, approach_distance, params)},
                                       std::pair{"tool", bodyColumns(gripper, approach_distance, params)}}) {
    const SweepHit sweep = sweepHits(scene, T_bin_grasp, columns);
    if (!sweep.hit) continue;
    judgement.obstacle = sweep.object;
    judgement.reason = hitReason(solid, sweep.object);
    return judgement;
  }
  judgement.reason = gripProblem(right, left, wider);
  if (!judgement.reason.empty()) return judgement;
  judgement.distance = opening - right.travel - left.travel;
  judgement.angle_deg = angleDeg(right.normal, -left.normal);
  if (judgement.angle_deg > params.max_antipodal_angle_deg) {
    judgement.reason = "jaw faces " + std::to_string(std::lround(judgement.angle_deg)) + " deg from opposite";
    return judgement;
  }
  judgement.ok = true;
  judgement.object = judgement.touched;
  return judgement;
}

}  // namespace binpick::emptying::detail
