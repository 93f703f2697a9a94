// PickTruthParams, TrueScene and judgePick: inputs checked, then the gripper's own judge.
#include "binpick/emptying/pick_truth.hpp"

#include <cmath>

#include "binpick/core/error.hpp"
#include "pick_rays.hpp"

namespace binpick::emptying {
namespace {

const std::string kOwner = "PickTruthParams";

bool positiveUpTo(double value, double high) { return std::isfinite(value) && value > 0.0 && value <= high; }

// A metre-sized spacing or tolerance is a unit slip (millimetres typed as metres), and one of
// micrometres would cast millions of rays: both refused.
constexpr double kMaxLength = 0.05;     // metres
constexpr double kMinSpacing = 0.0001;  // metres

std::vector<simulation::RenderObject> sceneObjects(const io::TriangleMesh& part,
                                                   const std::vector<Eigen::Isometry3d>& T_bin_objects,
                                                   const io::TriangleMesh& bin) {
  std::vector<simulation::RenderObject> objects;
  for (const Eigen::Isometry3d& pose : T_bin_objects) {
    objects.push_back({&part, pose, static_cast<int32_t>(objects.size())});
  }
  objects.push_back({&bin, Eigen::Isometry3d::Identity(), PickJudgement::kBin});
  return objects;
}

const io::TriangleMesh& requireValidPart(const io::TriangleMesh& part) {
  if (part.empty()) throw core::Error("TrueScene: the part mesh has no triangles");
  io::validateMesh(part, "TrueScene part");
  return part;
}

bool isRigid(const Eigen::Isometry3d& pose) {
  if (!pose.matrix().allFinite()) return false;
  const Eigen::Matrix3d r = pose.linear();
  return (r.transpose() * r - Eigen::Matrix3d::Identity()).norm() < 1e-6 && r.determinant() > 0.0;
}

}  // namespace

void PickTruthParams::validate() const {
  core::requireField(positiveUpTo(surface_tolerance, kMaxLength), kOwner, "surface_tolerance", "in (0, 0.05]",
                     surface_tolerance);
  core::requireField(positiveUpTo(max_axis_angle_deg, 90.0), kOwner, "max_axis_angle_deg", "in (0, 90]",
                     max_axis_angle_deg);
  core::requireField(positiveUpTo(max_antipodal_angle_deg, 90.0), kOwner, "max_antipodal_angle_deg", "in (0, 90]",
                     max_antipodal_angle_deg);
  core::requireField(positiveUpTo(sample_spacing, kMaxLength) && sample_spacing >= kMinSpacing, kOwner,
                     "sample_spacing", "in [0.0001, 0.05]", sample_spacing);
  core::requireField(positiveUpTo(collision_spacing, kMaxLength) && collision_spacing >= kMinSpacing, kOwner,
                     "collision_spacing", "in [0.0001, 0.05]", collision_spacing);
}

TrueScene::TrueScene(const io::TriangleMesh& part, const std::vector<Eigen::Isometry3d>& T_bin_objects,
                     const simulation::BinInterior& bin)
    : parts_(static_cast<int>(T_bin_objects.size())),
      caster_(sceneObjects(requireValidPart(part), T_bin_objects, simulation::binMesh(bin))) {}

PickJudgement judgePick(const TrueScene& scene, const Eigen::Isometry3d& T_bin_grasp,
                        const picking::GripperParams& gripper, double approach_distance, const PickTruthParams& params,
                        double opening) {
  params.validate();
  gripper.validate();
  if (!(std::isfinite(approach_distance) && approach_distance >= 0.0)) {
    throw core::Error("judgePick: approach_distance must be finite and >= 0 (got " + std::to_string(approach_distance) +
                      ")");
  }
  if (!isRigid(T_bin_grasp)) throw core::Error("judgePick: T_bin_grasp is not a finite rigid transform");
  if (gripper.type == picking::GripperType::Suction) {
    return detail::judgeSuction(scene, T_bin_grasp, gripper, approach_distance, params);
  }
  return detail::judgeParallel(scene, T_bin_grasp, gripper, approach_distance, opening, params);
}

}  // namespace binpick::emptying
