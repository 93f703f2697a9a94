// The built-in parts. To add one: write a `make...()` below returning a Part whose mesh is
// centred with `centredOnVolumeCentroid` and whose symmetry lists every proper rotation that maps
// it onto itself, then add a row to kRecipes.
#include "binpick/simulation/parts.hpp"

#include <array>
#include <initializer_list>

#include "binpick/io/error.hpp"
#include "mesh_geometry.hpp"

namespace binpick::sim {
namespace {

// Profiles are easier to read and check in millimetres; meshes are in metres.
std::vector<Eigen::Vector2d> millimetres(std::initializer_list<std::array<double, 2>> points) {
  std::vector<Eigen::Vector2d> profile;
  for (const auto& p : points) profile.emplace_back(p[0] * 1e-3, p[1] * 1e-3);
  return profile;
}

// The model frame of every part is at its volume centroid, so that poses (and the rotations of
// their symmetries) are about a point that does not depend on how the profile was drawn.
TriangleMesh centredOnVolumeCentroid(const TriangleMesh& mesh) {
  return detail::translated(mesh, -detail::volumeCentroid(mesh));
}

// An L with unequal legs (80 mm along x, 50 mm along y, both 8 mm thick) extruded 30 mm. Unequal
// legs remove the mirror about the diagonal, so no half-turn maps it onto itself: identity only.
Part makeLBracket() {
  const auto profile = millimetres({{0, 0}, {80, 0}, {80, 8}, {8, 8}, {8, 50}, {0, 50}});
  return {"l_bracket", "L bracket, legs 80 x 50 mm, 8 mm thick, 30 mm wide",
          centredOnVolumeCentroid(makePrism(profile, 0.030)), Symmetry{}};
}

// A lever clamp: a 90 mm bar with a chamfered tip, a step up to a taller jaw and a notch in the
// jaw, extruded 20 mm. The profile has no mirror line and no rotational symmetry: identity only.
Part makeClamp() {
  const auto profile = millimetres({{0, 0},
                                    {90, 0},
                                    {90, 6},
                                    {86, 10},
                                    {55, 10},
                                    {55, 14},
                                    {20, 14},
                                    {20, 30},
                                    {12, 30},
                                    {12, 22},
                                    {6, 22},
                                    {6, 30},
                                    {0, 30}});
  return {"clamp", "lever clamp, 90 x 30 mm with a step and a jaw notch, 20 mm thick",
          centredOnVolumeCentroid(makePrism(profile, 0.020)), Symmetry{}};
}

struct PartRecipe {
  const char* name;
  Part (*build)();
};

constexpr std::array<PartRecipe, 2> kRecipes{{
    {"l_bracket", &makeLBracket},
    {"clamp", &makeClamp},
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
  throw Error("makePart: unknown part '" + name + "' (known: " + known + ")");
}

}  // namespace binpick::sim
