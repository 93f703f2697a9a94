// Parallel-jaw grasps: two opposite faces no wider apart than the stroke, both fingers touching
// them (over an area, or along a line on a curved surface), and the fingers' path and the tool
// body free of the part.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "grasp_proposals.hpp"

namespace binpick::picking {
namespace {

constexpr int kContactColumns = 3;  // area samples across the finger (y)
constexpr int kContactRows = 5;     // area samples along the approach (z)
constexpr int kLineSamples = 7;     // samples along each of the two contact lines
constexpr double kMinContactShare = 0.5;
// A contact line holds when at least this share of the finger's width (or depth, the shorter)
// long: 4.8 mm on the default 12 mm finger. The 7 samples along a 20 mm finger lie 2.9 mm apart,
// so a 6 mm flange's rim, held across the flange's diameter over its whole thickness, touches two
// of them (5.7 mm); half the finger, as for an area, asked for three, which a rim thinner than
// 8.6 mm gives only where it happens to span them.
constexpr double kMinLineShare = 0.4;
constexpr double kMinWidth = 0.001;        // metres: thinner walls are not gripped across
constexpr double kTipPastContact = 0.002;  // metres of finger beyond a contact taken near the tips
// Metres the fingertips stay short of the part's far side along the approach: a part lying on that
// side lies on the floor or on its neighbours, and the planner grows the fingers by its collision
// margin (2 mm) against what the camera measured there; a 10 mm shaft still takes the contact on
// its axis, 2 mm from the tips.
constexpr double kTipShortOfFarSide = 0.0025;
// Metres the tool body behind the fingers keeps from the part between them: the planner grows the
// body by its collision margin (2 mm) against the measured cloud, and the part is in that cloud.
constexpr double kBodyClearance = 0.003;
constexpr double kStep = 1e-6;     // metres: a ray restarts this far past a surface it crossed
constexpr int kMaxCrossings = 16;  // surfaces followed along one closing line

// How one finger touches its face.
struct FingerContact {
  double area_share = 0.0;   // of the finger's contact rectangle
  double line_length = 0.0;  // metres: the longer of the two lines through the contact point
};

// Whether the finger's contact face, at `on_face` (grasp frame x = side * width / 2), touches a face
// whose outward normal is side * x, within the tolerance.
bool touches(const SurfaceModel& surface, RayScratch& rays, const Eigen::Vector3d& on_face, const Eigen::Vector3d& x,
             const GripperParams& gripper, const GraspGenerationParams& params, double antipodal_cos) {
  const double standoff = gripper.finger_thickness;  // the ray starts where the finger's back is
  const auto hit = surface.castRay(on_face + standoff * x, -x, standoff + params.contact_tolerance, rays);
  return hit && std::abs(hit->distance - standoff) <= params.contact_tolerance && hit->normal.dot(x) >= antipodal_cos;
}

// One finger (centred on the grasp frame's yz, at x = side * width / 2) on its face: the share of
// its rectangle that touches, and the contact lines through the point at `contact_along` on the
// finger's axis. A flat face touches over the rectangle; a cylinder only along its generator, which
// holds it as well when the line is long enough (a shaft between flat jaws).
FingerContact fingerContact(const SurfaceModel& surface, RayScratch& rays, const Eigen::Isometry3d& T_model_grasp,
                            double width, double side, double contact_along, const GripperParams& gripper,
                            const GraspGenerationParams& params, double antipodal_cos) {
  const Eigen::Vector3d x = side * T_model_grasp.linear().col(0);
  const Eigen::Vector3d y = T_model_grasp.linear().col(1), z = T_model_grasp.linear().col(2);
  const Eigen::Vector3d face_centre = T_model_grasp.translation() + 0.5 * width * x;
  const auto touchesAt = [&](double across, double along) {
    return touches(surface, rays, face_centre + across * y + along * z, x, gripper, params, antipodal_cos);
  };
  FingerContact contact;
  int touching = 0;
  for (int column = 0; column < kContactColumns; ++column) {
    for (int row = 0; row < kContactRows; ++row) {
      touching += touchesAt(gripper.finger_width * (column / (kContactColumns - 1.0) - 0.5),
                            gripper.finger_depth * (row / (kContactRows - 1.0) - 0.5));
    }
  }
  contact.area_share = static_cast<double>(touching) / (kContactColumns * kContactRows);
  int across_line = 0, along_line = 0;
  for (int i = 0; i < kLineSamples; ++i) {
    const double t = i / (kLineSamples - 1.0) - 0.5;
    across_line += touchesAt(gripper.finger_width * t, contact_along);
    along_line += touchesAt(0.0, gripper.finger_depth * t);
  }
  contact.line_length = std::max(across_line * gripper.finger_width, along_line * gripper.finger_depth) / kLineSamples;
  return contact;
}

// Part points inside a finger (on its way in along the approach, or closed) or the tool body
// (grown by kBodyClearance).
bool gripperHitsPart(const SurfaceModel& surface, const Eigen::Isometry3d& T_model_grasp, double width,
                     const GripperParams& gripper, const GraspGenerationParams& params) {
  const Eigen::Isometry3d T_grasp_model = T_model_grasp.inverse();
  const double finger_inner = 0.5 * width + params.contact_tolerance;  // the contact face itself is not in the way
  const double finger_outer = 0.5 * width + gripper.finger_thickness;
  const double root = -0.5 * gripper.finger_depth;
  const double tool_end = -gripper.toolBack();
  for (const Eigen::Vector3d& point : surface.obstaclePoints()) {
    const Eigen::Vector3d local = T_grasp_model * point;
    if (local.z() < tool_end) continue;
    const bool in_finger_path = local.z() <= -root && std::abs(local.x()) > finger_inner &&
                                std::abs(local.x()) < finger_outer && std::abs(local.y()) < 0.5 * gripper.finger_width;
    const bool in_tool =
        local.z() < root + kBodyClearance && local.head<2>().norm() < gripper.tool_radius + kBodyClearance;
    if (in_finger_path || in_tool) return true;
  }
  return false;
}

// Where the far jaw can touch on the closing line into the part from a sample: the first surface
// that leaves the part (a wall held across its thickness, the other finger in the hole behind it)
// and the last one (the part held across its whole extent on that line: a ring across its
// diameter), each when it faces opposite the sample and lies within the stroke.
std::vector<double> farContactWidths(const SurfaceModel& surface, RayScratch& rays, const SurfaceSample& sample,
                                     double stroke, double antipodal_cos) {
  const Eigen::Vector3d into = -sample.normal;
  const double reach = std::max(stroke, 2.0 * surface.radius());  // beyond the stroke: is the part still there?
  std::vector<double> widths;
  double travelled = 0.0;   // to the last surface crossed
  bool last_holds = false;  // it faces opposite the sample (so it leaves the part) within the stroke
  for (int crossing = 0;; ++crossing) {
    if (crossing == kMaxCrossings) return widths;  // too many surfaces to tell the last
    const auto hit = surface.castRay(sample.point + (travelled + kStep) * into, into, reach - travelled - kStep, rays);
    if (!hit) break;
    travelled += kStep + hit->distance;
    last_holds = hit->normal.dot(into) >= antipodal_cos && travelled <= stroke;
    if (crossing == 0 && last_holds) widths.push_back(travelled);
  }
  if (last_holds && (widths.empty() || travelled > widths.front() + kMinWidth)) widths.push_back(travelled);
  return widths;
}

std::string facesLabel(const Eigen::Vector3d& closing, double width, bool on_lines) {
  std::string axis = directionLabel(closing);
  if (axis.size() == 2) axis = "+-" + axis.substr(1);  // both faces: "+-x"
  char millimetres[32];
  std::snprintf(millimetres, sizeof millimetres, "%.1f mm", width * 1e3);
  return "faces " + axis + ", " + millimetres + (on_lines ? ", on lines" : "");
}

// How far the part reaches beyond `from` along the unit `direction`.
double reachAlong(const SurfaceModel& surface, const Eigen::Vector3d& from, const Eigen::Vector3d& direction) {
  double reach = 0.0;
  for (const Eigen::Vector3d& point : surface.obstaclePoints()) reach = std::max(reach, (point - from).dot(direction));
  return reach;
}

// The proposal for jaws closing along the sample's normal with this approach, when both fingers
// hold and nothing is in their way. The fingers go no deeper than they must: the contact near
// their tips first, then at their middle; either way the tips stay kTipShortOfFarSide short of the
// part's far side (a gear lying on the floor is held across its rim above its lower edge, the tips
// clear of the floor).
std::optional<GraspProposal> jawsAt(const SurfaceModel& surface, RayScratch& rays, const SurfaceSample& sample,
                                    double width, const Eigen::Vector3d& approach, const GripperParams& gripper,
                                    const GraspGenerationParams& params, double antipodal_cos) {
  const Eigen::Vector3d closing = sample.normal;  // grasp x: from the far face to the sample's
  const Eigen::Vector3d contact_centre = sample.point - 0.5 * width * closing;
  const double min_line = kMinLineShare * std::min(gripper.finger_width, gripper.finger_depth);
  std::optional<double> part_past_contact;  // along the approach; measured once a finger holds
  for (const double contact_along : {0.5 * gripper.finger_depth - kTipPastContact, 0.0}) {
    GraspProposal proposal;
    proposal.T_model_grasp.linear() << closing, approach.cross(closing), approach;
    proposal.T_model_grasp.translation() = contact_centre - contact_along * approach;
    const auto holds = [&](const FingerContact& c) {
      return c.area_share >= kMinContactShare || c.line_length >= min_line;
    };
    const FingerContact near =
        fingerContact(surface, rays, proposal.T_model_grasp, width, 1.0, contact_along, gripper, params, antipodal_cos);
    if (!holds(near)) continue;  // the far finger need not be looked at
    if (!part_past_contact) part_past_contact = reachAlong(surface, contact_centre, approach);
    const double tip_past_contact = 0.5 * gripper.finger_depth - contact_along;
    if (tip_past_contact > *part_past_contact - kTipShortOfFarSide) continue;
    const FingerContact far = fingerContact(surface, rays, proposal.T_model_grasp, width, -1.0, contact_along, gripper,
                                            params, antipodal_cos);
    const double area = std::min(near.area_share, far.area_share);
    const bool on_area = area >= kMinContactShare;
    if (!on_area && std::min(near.line_length, far.line_length) < min_line) continue;
    if (gripperHitsPart(surface, proposal.T_model_grasp, width, gripper, params)) continue;
    // Lines hold less surely than faces: they rank after every face, by closeness to the centre.
    proposal.margin = on_area ? (area - kMinContactShare) / (1.0 - kMinContactShare) : 0.0;
    proposal.patch = sample.patch;
    proposal.where = facesLabel(closing, width, !on_area);
    proposal.width = width;
    return proposal;
  }
  return std::nullopt;
}

}  // namespace

std::vector<GraspProposal> proposeParallelGrasps(const SurfaceModel& surface, const GripperParams& gripper,
                                                 const GraspGenerationParams& params) {
  const double antipodal_cos = std::cos(params.max_antipodal_angle_deg * M_PI / 180.0);
  RayScratch rays;
  std::vector<GraspProposal> proposals;
  for (const SurfaceSample& sample : surface.samples()) {
    for (const double width : farContactWidths(surface, rays, sample, gripper.stroke, antipodal_cos)) {
      if (width < kMinWidth) continue;
      const Eigen::Vector3d u = perpendicularTo(sample.normal), v = sample.normal.cross(u);
      for (int k = 0; k < params.approach_directions; ++k) {
        const double angle = 2.0 * M_PI * k / params.approach_directions;
        const Eigen::Vector3d approach = std::cos(angle) * u + std::sin(angle) * v;
        if (auto proposal = jawsAt(surface, rays, sample, width, approach, gripper, params, antipodal_cos)) {
          proposals.push_back(std::move(*proposal));
        }
      }
    }
  }
  return proposals;
}

}  // namespace binpick::picking
