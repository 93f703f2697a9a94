#include "binpick/picking/grasp_generation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>

#include "binpick/core/error.hpp"
#include "grasp_proposals.hpp"
#include "rigid.hpp"

namespace binpick::picking {
namespace {

const std::string kOwner = "grasp_generation";

struct Ranked {
  GraspProposal proposal;
  double quality = 0.0;
};

// Closeness of the grasp to the centre of mass, in [0, 1]: a suction cup holds the part against
// the torque of the centre's distance from its axis; jaws against its distance from the grasp point.
double closenessToCentre(const SurfaceModel& surface, const Eigen::Isometry3d& T_model_grasp, GripperType type) {
  const Eigen::Vector3d offset = surface.centreOfMass() - T_model_grasp.translation();
  const Eigen::Vector3d axis = T_model_grasp.linear().col(2);
  const double lever = type == GripperType::Suction ? (offset - offset.dot(axis) * axis).norm() : offset.norm();
  return surface.radius() > 0.0 ? 1.0 - std::min(1.0, lever / surface.radius()) : 1.0;
}

// The turn about the continuous axis bringing `from` onto `to`'s half-plane about the axis; 0 when
// either lies on the axis.
double turnBetween(const Eigen::Vector3d& axis, const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const Eigen::Vector3d a = from - from.dot(axis) * axis, b = to - to.dot(axis) * axis;
  if (a.norm() < 1e-9 || b.norm() < 1e-9) return 0.0;
  return std::atan2(axis.dot(a.cross(b)), a.dot(b));
}

class SymmetryComparison {
 public:
  SymmetryComparison(const PartSymmetry& symmetry, GripperType type, const GraspGenerationParams& params)
      : symmetry_(symmetry),
        type_(type),
        distance_(params.min_separation),
        angle_cos_(std::cos(params.symmetry_angle_deg * M_PI / 180.0)) {}

  // Equal up to a symmetry of the part, within the separation and angle.
  bool same(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) const {
    for (const Eigen::Matrix3d& S : symmetry_.discrete) {
      Eigen::Isometry3d moved = Eigen::Isometry3d::Identity();
      moved.linear() = S;
      moved = moved * a;
      if (symmetry_.continuous_axis) moved = alignedAboutAxis(moved, b);
      if (close(moved, b)) return true;
    }
    return false;
  }

 private:
  Eigen::Isometry3d alignedAboutAxis(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) const {
    const Eigen::Vector3d axis = symmetry_.continuous_axis->normalized();
    double angle = turnBetween(axis, a.translation(), b.translation());
    // Grasp points on the axis: turn the approach instead.
    if (angle == 0.0) angle = turnBetween(axis, a.linear().col(2), b.linear().col(2));
    Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
    turn.linear() = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    return turn * a;
  }

  bool close(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) const {
    if ((a.translation() - b.translation()).norm() > distance_) return false;
    if (a.linear().col(2).dot(b.linear().col(2)) < angle_cos_) return false;
    // A cup is round: its turn about the approach does not matter. Jaws are alike: x or -x.
    return type_ == GripperType::Suction || std::abs(a.linear().col(0).dot(b.linear().col(0))) >= angle_cos_;
  }

  const PartSymmetry& symmetry_;
  GripperType type_;
  double distance_, angle_cos_;
};

// Best first; a grasp the same as a better one (after symmetry) is dropped; every face's best
// before any face's second, up to max_grasps; best first again.
std::vector<Ranked> select(std::vector<Ranked> ranked, const SymmetryComparison& comparison, int max_grasps) {
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const Ranked& a, const Ranked& b) { return a.quality > b.quality; });
  std::vector<Ranked> distinct;
  for (const Ranked& candidate : ranked) {
    const bool repeated = std::any_of(distinct.begin(), distinct.end(), [&](const Ranked& kept) {
      return comparison.same(candidate.proposal.T_model_grasp, kept.proposal.T_model_grasp);
    });
    if (!repeated) distinct.push_back(candidate);
  }
  std::map<int, int> taken_per_patch;
  std::vector<int> round_of(distinct.size());
  for (std::size_t i = 0; i < distinct.size(); ++i) round_of[i] = taken_per_patch[distinct[i].proposal.patch]++;
  std::vector<std::size_t> order(distinct.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return round_of[a] < round_of[b]; });
  if (order.size() > static_cast<std::size_t>(max_grasps)) order.resize(static_cast<std::size_t>(max_grasps));
  std::sort(order.begin(), order.end());  // distinct is best first
  std::vector<Ranked> selected;
  for (std::size_t i : order) selected.push_back(distinct[i]);
  return selected;
}

std::vector<Grasp> generate(const SurfaceModel& surface, const GripperParams& gripper, const PartSymmetry& symmetry,
                            const GraspGenerationParams& params) {
  const std::vector<GraspProposal> proposals = gripper.type == GripperType::Suction
                                                   ? proposeSuctionGrasps(surface, gripper, params)
                                                   : proposeParallelGrasps(surface, gripper, params);
  std::vector<Ranked> ranked;
  ranked.reserve(proposals.size());
  for (const GraspProposal& proposal : proposals) {
    const double closeness = closenessToCentre(surface, proposal.T_model_grasp, gripper.type);
    const double quality = params.margin_weight * proposal.margin + (1.0 - params.margin_weight) * closeness;
    ranked.push_back({proposal, std::clamp(quality, 0.0, 1.0)});
  }
  const SymmetryComparison comparison(symmetry, gripper.type, params);
  std::vector<Grasp> grasps;
  for (const Ranked& chosen : select(std::move(ranked), comparison, params.max_grasps)) {
    const std::string rank = std::to_string(grasps.size() + 1);
    Grasp grasp;
    grasp.name = gripperTypeName(gripper.type) + " " + rank + " (" + chosen.proposal.where + ")";
    grasp.T_model_grasp = chosen.proposal.T_model_grasp;
    grasp.quality = chosen.quality;
    grasp.width = chosen.proposal.width;
    grasps.push_back(grasp);
  }
  return grasps;
}

void validateInputs(const GripperParams& gripper, const PartSymmetry& symmetry, const GraspGenerationParams& params) {
  params.validate();
  gripper.validate();
  for (const Eigen::Matrix3d& rotation : symmetry.discrete) {
    const bool proper = rotation.allFinite() &&
                        (rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).norm() < 1e-6 &&
                        rotation.determinant() > 0.0;
    if (!proper) throw core::Error("symmetry.discrete: every entry must be a proper rotation");
  }
  if (symmetry.continuous_axis && !(symmetry.continuous_axis->allFinite() && symmetry.continuous_axis->norm() > 1e-9)) {
    throw core::Error("symmetry.continuous_axis must be a non-zero direction");
  }
}

}  // namespace

void GraspGenerationParams::validate() const {
  core::requireField(isPositive(sample_spacing), kOwner, "sample_spacing", "> 0", sample_spacing);
  core::requireField(max_samples >= 10, kOwner, "max_samples", ">= 10", max_samples);
  core::requireField(max_grasps >= 1, kOwner, "max_grasps", ">= 1", max_grasps);
  core::requireField(isNonNegative(min_separation), kOwner, "min_separation", ">= 0", min_separation);
  core::requireField(std::isfinite(symmetry_angle_deg) && symmetry_angle_deg >= 0.0 && symmetry_angle_deg <= 90.0,
                     kOwner, "symmetry_angle_deg", "in [0, 90]", symmetry_angle_deg);
  core::requireField(
      std::isfinite(max_antipodal_angle_deg) && max_antipodal_angle_deg >= 0.0 && max_antipodal_angle_deg <= 45.0,
      kOwner, "max_antipodal_angle_deg", "in [0, 45]", max_antipodal_angle_deg);
  core::requireField(isPositive(contact_tolerance), kOwner, "contact_tolerance", "> 0", contact_tolerance);
  core::requireField(approach_directions >= 1 && approach_directions <= 64, kOwner, "approach_directions", "in [1, 64]",
                     approach_directions);
  core::requireField(std::isfinite(margin_weight) && margin_weight >= 0.0 && margin_weight <= 1.0, kOwner,
                     "margin_weight", "in [0, 1]", margin_weight);
  core::requireField(std::isfinite(cup_clearance) && cup_clearance >= 0.0, kOwner, "cup_clearance", ">= 0",
                     cup_clearance);
  core::requireField(std::isfinite(tool_clearance) && tool_clearance >= 0.0, kOwner, "tool_clearance", ">= 0",
                     tool_clearance);
  core::requireField(std::isfinite(seal_reserve) && seal_reserve >= 0.0 && seal_reserve < 1.0, kOwner, "seal_reserve",
                     "in [0, 1)", seal_reserve);
}

Eigen::Vector3d perpendicularTo(const Eigen::Vector3d& direction) {
  int least = 0;
  for (int axis = 1; axis < 3; ++axis) {
    if (std::abs(direction[axis]) < std::abs(direction[least]) - 1e-9) least = axis;
  }
  const Eigen::Vector3d model_axis = Eigen::Vector3d::Unit(least);
  return (model_axis - model_axis.dot(direction) * direction).normalized();
}

std::string directionLabel(const Eigen::Vector3d& direction) {
  const double near_axis_cos = std::cos(10.0 * M_PI / 180.0);
  const char* names = "xyz";
  for (int axis = 0; axis < 3; ++axis) {
    if (std::abs(direction[axis]) >= near_axis_cos) {
      return std::string(direction[axis] > 0 ? "+" : "-") + names[axis];
    }
  }
  char text[64];
  std::snprintf(text, sizeof text, "(%.2f, %.2f, %.2f)", direction.x(), direction.y(), direction.z());
  return text;
}

std::vector<Grasp> generateGrasps(const io::TriangleMesh& model, const GripperParams& gripper,
                                  const PartSymmetry& symmetry, const GraspGenerationParams& params) {
  validateInputs(gripper, symmetry, params);
  return generate(SurfaceModel::fromMesh(model, params), gripper, symmetry, params);
}

std::vector<Grasp> generateGrasps(const io::PointCloud& model, const GripperParams& gripper,
                                  const PartSymmetry& symmetry, const GraspGenerationParams& params) {
  validateInputs(gripper, symmetry, params);
  return generate(SurfaceModel::fromCloud(model, params), gripper, symmetry, params);
}

}  // namespace binpick::picking
