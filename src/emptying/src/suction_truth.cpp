// The suction cup's judge: on a part's surface, square to it, sealing on one face, and a clear way in.
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "pick_rays.hpp"

namespace binpick::emptying::detail {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Where the cup's centre meets the scene: the grasp-frame point and normal of the surface.
struct Contact {
  Eigen::Vector3d point;   // grasp frame
  Eigen::Vector3d normal;  // grasp frame, outward
};

// What the surface under each disc sample is, against the face under the centre.
struct DiscSurvey {
  bool same_part_off = false;  // the same part, but a step or a drop beyond the seal tolerance
  bool falls_away = false;     // nothing, the bin, or another part below the face
  bool other_level = false;    // another part within the seal tolerance of the face
  bool other_above = false;    // another part standing above the face
};

DiscSurvey surveyDisc(const TrueScene& scene, const Eigen::Isometry3d& T_bin_grasp,
                      const picking::GripperParams& gripper, const PickTruthParams& params, double z_start, int part,
                      const Contact& contact) {
  std::vector<Eigen::Vector3d> origins;
  for (const Eigen::Vector2d& xy : discSamples(0.5 * gripper.cup_diameter, params.sample_spacing)) {
    origins.emplace_back(xy.x(), xy.y(), z_start);
  }
  const Eigen::Isometry3d T_grasp_bin = T_bin_grasp.inverse();
  DiscSurvey survey;
  for (const simulation::RayHit& hit : castFrom(scene, T_bin_grasp, origins, Eigen::Vector3d::UnitZ(), kInfinity)) {
    if (!hit.hit() || hit.object_id == PickJudgement::kBin) {
      survey.falls_away = true;
      continue;
    }
    const double height = (T_grasp_bin * hit.point - contact.point).dot(contact.normal);
    const bool level = std::abs(height) <= gripper.seal_tolerance;
    if (hit.object_id == part) {
      survey.same_part_off |= !level;
    } else if (level) {
      survey.other_level = true;
    } else if (height > 0.0) {
      survey.other_above = true;
    } else {
      survey.falls_away = true;
    }
  }
  return survey;
}

// Empty when the whole disc seals on the part under its centre.
std::string sealProblem(const DiscSurvey& survey) {
  if (survey.other_above) return "cup on a neighbour";
  if (survey.other_level) return survey.falls_away ? "cup over a gap" : "cup on a neighbour";
  if (survey.falls_away || survey.same_part_off) return "cup across an edge";
  return {};
}

// Where the line through (x, y) along the approach crosses a bent nose's body at the grasp: the
// z interval in which the line's distance to the body's axis is at most its radius (a quadratic
// in z) and its point lies along the axis within the body's length (linear in z). Empty: none.
std::optional<std::pair<double, double>> bentBodySpan(const picking::GripperParams& gripper,
                                                      const Eigen::Vector2d& xy) {
  const Eigen::Vector3d axis = gripper.bodyAxis();
  const Eigen::Vector3d offset = Eigen::Vector3d(xy.x(), xy.y(), 0.0) - gripper.bodyStart();
  const double along0 = offset.dot(axis);  // along the axis at z = 0, changing by axis.z() per z
  // |offset + z e_z|^2 - (along0 + z axis.z)^2 <= r^2
  const double a = 1.0 - axis.z() * axis.z();
  const double b = 2.0 * (offset.z() - along0 * axis.z());
  const double c = offset.squaredNorm() - along0 * along0 - gripper.tool_radius * gripper.tool_radius;
  const double discriminant = b * b - 4.0 * a * c;
  if (!(a > 0.0) || discriminant < 0.0) return std::nullopt;
  double lo = (-b - std::sqrt(discriminant)) / (2.0 * a), hi = (-b + std::sqrt(discriminant)) / (2.0 * a);
  // 0 <= along0 + z axis.z <= tool_length, axis.z < 0: z runs from the body's end to its start.
  lo = std::max(lo, (gripper.tool_length - along0) / axis.z());
  hi = std::min(hi, -along0 / axis.z());
  if (lo > hi) return std::nullopt;
  return std::make_pair(lo, hi);
}

// A bent nose's body as columns along the approach, each swept back by approach_distance.
std::vector<Column> bentBodyColumns(const picking::GripperParams& gripper, double approach_distance,
                                    const PickTruthParams& params) {
  const double r = gripper.tool_radius;
  const double reach = gripper.tool_length * gripper.bodyAxis().x();
  std::vector<Column> columns;
  for (const Eigen::Vector2d& xy : rectangleSamples(-r, reach + r, -r, r, params.collision_spacing)) {
    if (const auto span = bentBodySpan(gripper, xy)) {
      columns.push_back({xy, span->first - approach_distance, span->second});
    }
  }
  return columns;
}

// The cup and the body as columns along the approach, swept back by approach_distance. Within the
// cup's footprint a column reaches the sealed face's plane less the seal tolerance: the face itself
// is where the cup belongs.
std::vector<Column> toolColumns(const picking::GripperParams& gripper, double approach_distance,
                                const PickTruthParams& params, const Contact& contact) {
  const double cup_radius = 0.5 * gripper.cup_diameter;
  // A bent body has columns of its own; a straight one shares the cup's axis.
  const bool straight_body = !gripper.bent();
  const double body_radius = straight_body ? gripper.tool_radius : 0.0;
  const double body_back = -(gripper.cup_length + gripper.tool_length + approach_distance);
  const double cup_back = -(gripper.cup_length + approach_distance);
  const Eigen::Vector3d& n = contact.normal;
  std::vector<Column> columns;
  for (const Eigen::Vector2d& xy : discSamples(std::max(cup_radius, body_radius), params.collision_spacing)) {
    const double rho = xy.norm();
    const bool in_cup = rho <= cup_radius * (1.0 + 1e-9);
    const bool in_body = straight_body && rho <= body_radius * (1.0 + 1e-9);
    if (!in_cup && !in_body) continue;
    const double face_z = contact.point.z() - (n.x() * xy.x() + n.y() * xy.y()) / n.z();
    const double z_to = in_cup ? face_z - gripper.seal_tolerance : -gripper.cup_length;
    columns.push_back({xy, in_body ? body_back : cup_back, z_to});
  }
  if (gripper.bent()) {
    const std::vector<Column> body = bentBodyColumns(gripper, approach_distance, params);
    columns.insert(columns.end(), body.begin(), body.end());
  }
  return columns;
}

}  // namespace

PickJudgement judgeSuction(const TrueScene& scene, const Eigen::Isometry3d& T_bin_grasp,
                           const picking::GripperParams& gripper, double approach_distance,
                           const PickTruthParams& params) {
  PickJudgement judgement;
  // Rays start at the back of the cup: whatever lies between there and the disc is in its way.
  const double z_start = -std::max(gripper.cup_length, params.surface_tolerance);
  const simulation::RayHit centre =
      castFrom(scene, T_bin_grasp, {Eigen::Vector3d(0.0, 0.0, z_start)}, Eigen::Vector3d::UnitZ(), kInfinity)[0];
  if (centre.hit()) judgement.distance = z_start + centre.t;
  if (centre.hit() && centre.object_id >= 0) judgement.touched = centre.object_id;
  if (!centre.hit() || std::abs(judgement.distance) > params.surface_tolerance) {
    judgement.reason = "off the part";
    return judgement;
  }
  if (centre.object_id == PickJudgement::kBin) {
    judgement.reason = "cup on the bin";
    return judgement;
  }
  const Contact contact{Eigen::Vector3d(0.0, 0.0, judgement.distance),
                        T_bin_grasp.linear().transpose() * centre.normal};
  judgement.angle_deg = angleDeg(Eigen::Vector3d::UnitZ(), -contact.normal);
  if (judgement.angle_deg > params.max_axis_angle_deg) {
    judgement.reason = "tilted " + std::to_string(std::lround(judgement.angle_deg)) + " deg from the surface";
    return judgement;
  }
  judgement.reason = sealProblem(surveyDisc(scene, T_bin_grasp, gripper, params, z_start, judgement.touched, contact));
  if (!judgement.reason.empty()) return judgement;
  const SweepHit sweep = sweepHits(scene, T_bin_grasp, toolColumns(gripper, approach_distance, params, contact));
  if (sweep.hit) {
    judgement.obstacle = sweep.object;
    judgement.reason = hitReason("tool", sweep.object);
    return judgement;
  }
  judgement.ok = true;
  judgement.object = judgement.touched;
  return judgement;
}

}  // namespace binpick::emptying::detail
