#include "release_layout.hpp"

#include <algorithm>

namespace binpick::simulation::detail {
namespace {

// Random places tried for a part before the layer is closed: enough to fill most of the free
// area, few enough to stay cheap.
constexpr int kTriesPerPart = 32;

struct Release {
  Eigen::Isometry3d T_bin_model = Eigen::Isometry3d::Identity();
  Eigen::AlignedBox3d box;  // of the part at that pose, bin frame
};

Release randomRelease(double pile_top, const std::vector<Eigen::Vector3d>& points, const BinInterior& bin,
                      const PhysicsParams& params, double clearance, Rng& rng) {
  Release release;
  release.T_bin_model.linear() = uniformRotation(rng);
  Eigen::AlignedBox3d turned;  // extent of the rotated part around its model origin
  for (const auto& p : points) turned.extend(release.T_bin_model.linear() * p);
  // Any x, y keeping the footprint inside; the caller made sure the part fits in every orientation.
  const double x_limit = 0.5 * bin.length - clearance, y_limit = 0.5 * bin.width - clearance;
  const double x = uniform(rng, -x_limit - turned.min().x(), x_limit - turned.max().x());
  const double y = uniform(rng, -y_limit - turned.min().y(), y_limit - turned.max().y());
  const double lift = uniform(rng, params.drop_height_min, params.drop_height_max);
  release.T_bin_model.translation() = Eigen::Vector3d(x, y, pile_top + lift - turned.min().z());
  release.box = turned.translated(release.T_bin_model.translation());
  // Keep the collision shells of neighbours apart too.
  release.box.min().array() -= params.collision_margin;
  release.box.max().array() += params.collision_margin;
  return release;
}

}  // namespace

std::vector<Eigen::Isometry3d> releaseLayer(int wanted, double pile_top,
                                            const std::vector<Eigen::Vector3d>& extreme_points, const BinInterior& bin,
                                            const PhysicsParams& params, double wall_clearance, Rng& rng) {
  std::vector<Release> layer;
  while (static_cast<int>(layer.size()) < wanted) {
    bool placed = false;
    for (int attempt = 0; attempt < kTriesPerPart && !placed; ++attempt) {
      Release candidate = randomRelease(pile_top, extreme_points, bin, params, wall_clearance, rng);
      placed = std::none_of(layer.begin(), layer.end(),
                            [&](const Release& other) { return other.box.intersects(candidate.box); });
      if (placed) layer.push_back(std::move(candidate));
    }
    if (!placed) break;
  }
  std::vector<Eigen::Isometry3d> poses;
  for (const auto& release : layer) poses.push_back(release.T_bin_model);
  return poses;
}

}  // namespace binpick::simulation::detail
