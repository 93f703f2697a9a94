// Suction grasps: where the whole cup disc seals on the surface and the cup and tool are free.
#include <cmath>

#include "grasp_proposals.hpp"

namespace binpick::picking {
namespace {

// The surface under a disc point may turn this far from the disc's plane and still seal.
const double kSealNormalCos = std::cos(25.0 * M_PI / 180.0);
constexpr int kRimRays = 32;  // the rim's points are then at most 0.5% of the radius apart inward
constexpr int kInnerRays = 16;
constexpr int kMarginRings = 4;  // rings at 1.25, 1.5, 1.75 and 2 cup radii measure the margin

struct DiscFrame {
  Eigen::Vector3d centre, normal, x, y;  // normal: outward, the cup comes down along -normal
  // Point k of `rays` evenly spaced on the ring of `radius` in the disc's plane.
  Eigen::Vector3d onRing(double radius, int k, int rays) const {
    const double angle = 2.0 * M_PI * k / rays;
    return centre + radius * (std::cos(angle) * x + std::sin(angle) * y);
  }
};

// Casts its rays with a scratch of its own: one SealTest per thread.
class SealTest {
 public:
  SealTest(const SurfaceModel& surface, double tolerance, double height)
      : surface_(surface), tolerance_(tolerance), height_(height) {}

  // Every point of the ring (radius, rays) meets the surface within the tolerance of the plane,
  // on surface facing the cup, with nothing in between.
  bool ringSeals(const DiscFrame& disc, double radius, int rays) {
    for (int k = 0; k < rays; ++k) {
      if (!pointSeals(disc, disc.onRing(radius, k, rays))) return false;
    }
    return true;
  }

  // Nothing of the part stands above the plane beyond the tolerance over the ring (a wall beside
  // the cup, the flank of a groove it sits in); the surface may fall away there. The rays come
  // from beyond the whole part (`reach`): one starting inside a wall would find no face below it.
  bool ringClear(const DiscFrame& disc, double radius, int rays, double reach) {
    for (int k = 0; k < rays; ++k) {
      const auto hit =
          surface_.castRay(disc.onRing(radius, k, rays) + reach * disc.normal, -disc.normal, reach, scratch_);
      if (hit && reach - hit->distance > tolerance_) return false;
    }
    return true;
  }

  bool pointSeals(const DiscFrame& disc, const Eigen::Vector3d& on_plane) {
    const auto hit = surface_.castRay(on_plane + height_ * disc.normal, -disc.normal, height_ + tolerance_, scratch_);
    if (!hit) return false;                            // a gap or past an edge
    const double deviation = height_ - hit->distance;  // > 0: above the plane
    return std::abs(deviation) <= tolerance_ && hit->normal.dot(disc.normal) >= kSealNormalCos;
  }

 private:
  const SurfaceModel& surface_;
  double tolerance_, height_;
  RayScratch scratch_;
};

// Part points inside the cup (above the sealing surface) or the tool body behind it, both grown
// by `clearance`.
bool gripperHitsPart(const SurfaceModel& surface, const Eigen::Isometry3d& T_model_grasp, const GripperParams& gripper,
                     double clearance) {
  const Eigen::Isometry3d T_grasp_model = T_model_grasp.inverse();
  const double cup_radius = 0.5 * gripper.cup_diameter + clearance;
  const double tool_radius = gripper.tool_radius + clearance;
  const double cup_top = -2.0 * gripper.seal_tolerance;  // the sealed surface itself is not in the way
  const double tool_end = -gripper.toolBack() - clearance;
  for (const Eigen::Vector3d& point : surface.obstaclePoints()) {
    const Eigen::Vector3d local = T_grasp_model * point;
    if (local.z() > cup_top || local.z() < tool_end) continue;
    const double radial = local.head<2>().norm();
    const bool in_cup = local.z() >= -gripper.cup_length && radial < cup_radius;
    const bool in_tool = local.z() < -gripper.cup_length + clearance && radial < tool_radius;
    if (in_cup || in_tool) return true;
  }
  return false;
}

}  // namespace

std::vector<GraspProposal> proposeSuctionGrasps(const SurfaceModel& surface, const GripperParams& gripper,
                                                const GraspGenerationParams& params) {
  const double radius = 0.5 * gripper.cup_diameter;
  // Rays start this far above the disc: anything of the part closer above it is in the cup's way.
  SealTest seal(surface, (1.0 - params.seal_reserve) * gripper.seal_tolerance,
                std::max(radius, 4.0 * gripper.seal_tolerance));
  const double reach = 2.0 * surface.radius() + radius + params.cup_clearance;  // from beyond the part
  std::vector<GraspProposal> proposals;
  for (const SurfaceSample& sample : surface.samples()) {
    DiscFrame disc{sample.point, sample.normal, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    const Eigen::Vector3d approach = -sample.normal;
    disc.x = perpendicularTo(approach);
    disc.y = approach.cross(disc.x);
    if (!seal.pointSeals(disc, disc.centre) || !seal.ringSeals(disc, 0.5 * radius, kInnerRays) ||
        !seal.ringSeals(disc, radius, kRimRays) ||
        !seal.ringClear(disc, radius + params.cup_clearance, kRimRays, reach)) {
      continue;
    }
    GraspProposal proposal;
    proposal.T_model_grasp.linear() << disc.x, disc.y, approach;
    proposal.T_model_grasp.translation() = sample.point;
    if (gripperHitsPart(surface, proposal.T_model_grasp, gripper, params.tool_clearance)) continue;
    int sealing_rings = 0;
    while (sealing_rings < kMarginRings &&
           seal.ringSeals(disc, radius * (1.0 + (sealing_rings + 1.0) / kMarginRings), kRimRays)) {
      ++sealing_rings;
    }
    proposal.margin = static_cast<double>(sealing_rings) / kMarginRings;
    proposal.patch = sample.patch;
    proposal.where = "face " + directionLabel(sample.normal);
    proposals.push_back(proposal);
  }
  return proposals;
}

}  // namespace binpick::picking
