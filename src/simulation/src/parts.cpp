// The built-in parts. To add one: write a `make...()` returning a Part whose mesh is centred with
// `centredOnVolumeCentroid` and whose symmetry lists every proper rotation that maps it onto
// itself (parts_prismatic.cpp, parts_turned.cpp), declare it in part_recipes.hpp and add a row to
// kRecipes.
#include "binpick/simulation/parts.hpp"

#include <array>

#include "binpick/core/error.hpp"
#include "mesh_geometry.hpp"
#include "part_recipes.hpp"

namespace binpick::simulation {
namespace detail {

std::vector<Eigen::Vector2d> millimetres(std::initializer_list<std::array<double, 2>> points) {
  std::vector<Eigen::Vector2d> profile;
  for (const auto& p : points) profile.emplace_back(p[0] * 1e-3, p[1] * 1e-3);
  return profile;
}

io::TriangleMesh centredOnVolumeCentroid(const io::TriangleMesh& mesh) {
  return translated(mesh, -volumeCentroid(mesh));
}

}  // namespace detail

namespace {

struct PartRecipe {
  const char* name;
  Part (*build)();
};

constexpr std::array<PartRecipe, 7> kRecipes{{
    {"l_bracket", &detail::makeLBracket},
    {"clamp", &detail::makeClamp},
    {"gear", &detail::makeGear},
    {"l_bracket_long", &detail::makeLBracketLong},
    {"ring_magnet", &detail::makeRingMagnet},
    {"switch", &detail::makeSwitch},
    {"bulge", &detail::makeBulge},
}};

}  // namespace

std::vector<std::string> partNames() {
  std::vector<std::string> names;
  for (const auto& recipe : kRecipes) names.emplace_back(recipe.name);
  return names;
}

Part makePart(const std::string& name) {
  for (const auto& recipe : kRecipes) {
    if (name == recipe.name) return recipe.build();
  }
  std::string known;
  for (const auto& recipe : kRecipes) known += std::string(known.empty() ? "" : ", ") + recipe.name;
  throw core::Error("makePart: unknown part '" + name + "' (known: " + known + ")");
}

Part partFromMesh(const std::string& name, io::TriangleMesh mesh) {
  const io::FoundSymmetry found = io::findSymmetry(mesh);
  return {name, "a user's mesh; symmetry from the mesh: " + found.description, std::move(mesh), found.symmetry};
}

}  // namespace binpick::simulation
