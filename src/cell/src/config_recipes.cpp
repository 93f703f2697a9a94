// The `recipes:` list: the parts the cell can pick, each with its model, settings and grasps.
#include <set>

#include "binpick/cell/grasps_file.hpp"
#include "binpick/core/pose_yaml.hpp"
#include "config_sections.hpp"

namespace binpick::cell {
namespace {

// grasps: a list written in place, a string naming a grasps file (`binpick grasps`), or absent:
// then they are generated from the model when the cell is prepared (cell_setup.cpp).
std::vector<picking::Grasp> readGrasps(core::YamlSection& recipe, const std::string& path, const std::string& origin,
                                       const PathResolver& resolve) {
  recipe.skip("grasps");
  if (!recipe.has("grasps")) return {};
  const YAML::Node grasps = recipe.node()["grasps"];
  if (!grasps.IsScalar()) return readGraspList(grasps, path, origin);
  const std::string file = resolve(grasps.as<std::string>());
  try {
    return readGraspsFile(file);
  } catch (const core::Error& e) {
    throw core::Error(origin + ": " + path + "grasps: " + e.what());
  }
}

constexpr int kMaxSymmetryOrder = 360;

// symmetry: {rotations: [[...rotation values...], ...], convention: NAME, continuous_axis: [x, y, z]}
// or {order: N, axis: [x, y, z]}: N-fold about the axis. None: found from the model's mesh
// when the cell starts (cell_setup.cpp).
std::optional<picking::PartSymmetry> readSymmetry(core::YamlSection s) {
  if (s.isNull()) return std::nullopt;
  picking::PartSymmetry symmetry;
  int order = 1;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  bool continuous = false;
  s.read("order", order);
  s.readVector3("axis", axis);
  s.read("continuous", continuous);
  s.finish();
  // Each fold is a rotation kept, and every grasp is tried in each: a part looking the same
  // after 360 turns is round, which `continuous: true` says without a list.
  if (order < 1 || order > kMaxSymmetryOrder) {
    s.fail("order", "must be in [1, " + std::to_string(kMaxSymmetryOrder) + "] (got " + std::to_string(order) + ")");
  }
  if (!(axis.norm() > 1e-9) || !axis.allFinite()) s.fail("axis", "must be a non-zero direction");
  axis.normalize();
  if (continuous) symmetry.continuous_axis = axis;
  for (int k = 1; k < order; ++k) {
    symmetry.discrete.push_back(Eigen::AngleAxisd(2.0 * M_PI * k / order, axis).toRotationMatrix());
  }
  return symmetry;
}

RecipeConfig readRecipe(core::YamlSection s, const std::string& path, const std::string& origin,
                        const PathResolver& resolve) {
  RecipeConfig recipe;
  s.read("name", recipe.name);
  s.read("model", recipe.model_file);
  s.read("cache", recipe.model_cache);
  s.read("settings", recipe.settings_file);
  recipe.grasps = readGrasps(s, path, origin, resolve);
  // A flip of the part about x (e.g. a plate that may lie either way up) is written as order 2
  // about x; a turned part as continuous about its axis.
  recipe.symmetry = readSymmetry(s.child("symmetry"));
  s.finish();
  if (recipe.name.empty()) s.fail("name", "is needed");
  if (recipe.model_file.empty()) s.fail("model", "is needed");
  recipe.model_file = resolve(recipe.model_file);
  recipe.model_cache = resolve(recipe.model_cache);
  recipe.settings_file = resolve(recipe.settings_file);
  return recipe;
}

}  // namespace

std::vector<RecipeConfig> readRecipes(const YAML::Node& list, const std::string& origin, const PathResolver& resolve) {
  if (!list || !list.IsSequence() || list.size() == 0) {
    throw core::Error(origin + ": recipes needs a list of at least one recipe");
  }
  std::vector<RecipeConfig> recipes;
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = "recipes[" + std::to_string(i) + "].";
    recipes.push_back(readRecipe(core::YamlSection(list[i], path, origin), path, origin, resolve));
    if (!names.insert(recipes.back().name).second) {
      throw core::Error(origin + ": " + path + "name \"" + recipes.back().name + "\" is used twice");
    }
  }
  return recipes;
}

}  // namespace binpick::cell
