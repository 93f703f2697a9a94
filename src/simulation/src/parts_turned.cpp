// The turned built-in parts: a profile drawn in millimetres (r, z), revolved about z.
#include "part_recipes.hpp"

namespace binpick::simulation::detail {

// A ring magnet: the rectangle r in [12, 25] mm, z in [-5, 5] mm revolved with 64 segments
// (outer diameter 50 mm, bore 24 mm, 10 mm thick). Symmetry: the continuous axis z and the flip
// over (a half-turn about x), as the discrete set {I, Rx(pi)}. The mesh itself is only 64-fold
// symmetric about z (facets at multiples of 2 pi / 64, the first on +x, so Rx(pi) is exact).
Part makeRingMagnet() {
  constexpr int kSegments = 64;
  const auto profile = millimetres({{12, -5}, {25, -5}, {25, 5}, {12, 5}});
  Symmetry symmetry;
  symmetry.discrete.push_back(Eigen::AngleAxisd(3.14159265358979323846, Eigen::Vector3d::UnitX()).toRotationMatrix());
  symmetry.continuous_axis = Eigen::Vector3d::UnitZ();
  return {"ring_magnet", "ring magnet, 50 mm outer and 24 mm inner diameter, 10 mm thick",
          centredOnVolumeCentroid(makeLathe(profile, kSegments)), symmetry};
}

}  // namespace binpick::simulation::detail
