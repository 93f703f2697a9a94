// chooseCup: the cup that lets a part be picked in the most of the ways it can lie (cup_choice.hpp).
#include "binpick/picking/cup_choice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "binpick/core/error.hpp"
#include "grasp_candidates.hpp"

namespace binpick::picking {
namespace {

const std::string kOwner = "cup_choice";

// `count` directions spread evenly over the unit sphere (a Fibonacci lattice: equal areas, no
// seed, the same every time).
std::vector<Eigen::Vector3d> sphereDirections(int count) {
  const double golden_turn = M_PI * (3.0 - std::sqrt(5.0));
  std::vector<Eigen::Vector3d> directions;
  directions.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / count;
    const double ring = std::sqrt(std::max(0.0, 1.0 - z * z));
    directions.emplace_back(ring * std::cos(golden_turn * i), ring * std::sin(golden_turn * i), z);
  }
  return directions;
}

// Every approach the grasps offer under the symmetry, as the planner repeats them.
std::vector<Eigen::Vector3d> approaches(const std::vector<Grasp>& grasps, const PartSymmetry& symmetry,
                                        int continuous_steps) {
  PickParams candidates;
  candidates.grasps = grasps;
  candidates.symmetry = symmetry;
  candidates.continuous_symmetry_steps = continuous_steps;
  std::vector<Eigen::Vector3d> result;
  for (const GraspCandidate& candidate : symmetricGraspCandidates(candidates)) {
    result.push_back(candidate.T_model_grasp.linear().col(2));
  }
  return result;
}

}  // namespace

void CupChoiceParams::validate() const {
  for (const double diameter : series) {
    core::requireField(std::isfinite(diameter) && diameter > 0.0, kOwner, "series", "diameters > 0", diameter);
  }
  core::requireField(min_gain > 0.0 && min_gain <= 1.0, kOwner, "min_gain", "in (0, 1]", min_gain);
  core::requireField(max_tilt_deg >= 0.0 && max_tilt_deg <= 180.0, kOwner, "max_tilt_deg", "in [0, 180]", max_tilt_deg);
  core::requireField(directions >= 10 && directions <= 1000000, kOwner, "directions", "in [10, 1000000]", directions);
  core::requireField(continuous_steps >= 1 && continuous_steps <= 3600, kOwner, "continuous_steps", "in [1, 3600]",
                     continuous_steps);
}

double upwardShare(const std::vector<Grasp>& grasps, const PartSymmetry& symmetry, const CupChoiceParams& params) {
  params.validate();
  if (grasps.empty()) return 0.0;
  const std::vector<Eigen::Vector3d> offered = approaches(grasps, symmetry, params.continuous_steps);
  const double min_cosine = std::cos(params.max_tilt_deg * M_PI / 180.0);
  int facing_up = 0;
  for (const Eigen::Vector3d& up : sphereDirections(params.directions)) {
    // A grasp faces up when its approach (into the part) is within the tilt of -up.
    const bool any = std::any_of(offered.begin(), offered.end(),
                                 [&](const Eigen::Vector3d& approach) { return -approach.dot(up) >= min_cosine; });
    facing_up += any ? 1 : 0;
  }
  return static_cast<double>(facing_up) / params.directions;
}

std::string describeCupChoice(const CupChoice& choice) {
  const auto millimetres = [](double metres) {
    char text[32];
    std::snprintf(text, sizeof(text), "%g mm", 1000.0 * metres);
    return std::string(text);
  };
  std::string text = millimetres(choice.diameter) + " cup (";
  for (std::size_t i = 0; i < choice.options.size(); ++i) {
    const CupOption& option = choice.options[i];
    text += (i == 0 ? "of " : ", ") + millimetres(option.diameter) + ": " +
            std::to_string(std::lround(100.0 * option.upward)) + "%" +
            (i == 0 ? " of orientations with a grasp facing up" : "");
  }
  return text + ")";
}

CupChoice chooseCup(const io::TriangleMesh& model, const GripperParams& gripper, const PartSymmetry& symmetry,
                    const GraspGenerationParams& generation, const CupChoiceParams& params) {
  params.validate();
  gripper.validate();
  if (gripper.type != GripperType::Suction) throw core::Error("chooseCup: the gripper is not a suction gripper");
  std::vector<double> diameters = {gripper.cup_diameter};
  for (const double smaller : params.series) {
    if (smaller < gripper.cup_diameter) diameters.push_back(smaller);
  }
  std::sort(diameters.begin() + 1, diameters.end(), std::greater<>());
  CupChoice choice;
  for (const double diameter : diameters) {
    GripperParams cup = gripper;
    cup.cup_diameter = diameter;
    const std::vector<Grasp> grasps = generateGrasps(model, cup, symmetry, generation);
    choice.options.push_back({diameter, static_cast<int>(grasps.size()), upwardShare(grasps, symmetry, params)});
  }
  const auto best = std::max_element(choice.options.begin(), choice.options.end(),
                                     [](const CupOption& a, const CupOption& b) { return a.upward < b.upward; });
  choice.diameter = gripper.cup_diameter;
  if (best->upward < choice.options.front().upward + params.min_gain) return choice;
  // The options after the gripper's own go from large to small: the first close enough to the best.
  for (auto option = choice.options.begin() + 1; option != choice.options.end(); ++option) {
    if (option->upward >= best->upward - params.min_gain) {
      choice.diameter = option->diameter;
      break;
    }
  }
  return choice;
}

}  // namespace binpick::picking
