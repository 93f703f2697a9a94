#include "voxel_grid.hpp"

#include <cmath>
#include <string>

#include "binpick/core/error.hpp"

namespace binpick::estimation {

SceneVoxelGrid::SceneVoxelGrid(const std::vector<Eigen::Vector3f>& scene_points, float voxel_size)
    : voxel_size_(voxel_size) {
  if (!(voxel_size > 0.0f) || !std::isfinite(voxel_size)) throw core::Error("voxel grid: voxel size must be positive");
  if (scene_points.empty()) return;
  Eigen::Vector3f lo = scene_points[0], hi = scene_points[0];
  for (std::size_t i = 0; i < scene_points.size(); ++i) {
    const Eigen::Vector3f& p = scene_points[i];
    if (!p.allFinite()) throw core::Error("voxel grid: scene point " + std::to_string(i) + " is not finite");
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  // One voxel of margin so that the neighbours of boundary points exist (min x of eq. 3 moves).
  origin_ = lo - Eigen::Vector3f::Constant(voxel_size);
  const Eigen::Vector3f extent = (hi - origin_) / voxel_size;
  if (!(extent.maxCoeff() < 1e7f))
    throw core::Error("voxel grid: the scene spans over 10^7 voxels along an axis; crop it to the bin");
  for (int a = 0; a < 3; ++a) {
    dims_[a] = static_cast<int64_t>(std::floor(extent[a])) + 2;
    block_dims_[a] = (dims_[a] + 7) / 8;
    dims_f_[a] = static_cast<float>(dims_[a]);
  }
  const int64_t block_count = block_dims_.prod();
  if (block_count > (int64_t{1} << 26)) {
    throw core::Error("voxel grid: the scene spans " + std::to_string(block_count) +
                      " blocks of voxels; crop the scene to the bin");
  }
  blocks_.assign(static_cast<std::size_t>(block_count), -1);
  for (std::size_t i = 0; i < scene_points.size(); ++i) {
    const Eigen::Vector3f q = (scene_points[i] - origin_) / voxel_size;
    const auto x = static_cast<int64_t>(q.x()), y = static_cast<int64_t>(q.y()), z = static_cast<int64_t>(q.z());
    for (int64_t dz = -1; dz <= 1; ++dz)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dx = -1; dx <= 1; ++dx) write(x + dx, y + dy, z + dz, static_cast<int32_t>(i));
  }
}

void SceneVoxelGrid::write(int64_t x, int64_t y, int64_t z, int32_t value) {
  if (x < 0 || y < 0 || z < 0 || x >= dims_.x() || y >= dims_.y() || z >= dims_.z()) return;
  int32_t& block = blocks_[blockIndex(x >> 3, y >> 3, z >> 3)];
  if (block < 0) {
    block = static_cast<int32_t>(cells_.size() / 512);
    cells_.resize(cells_.size() + 512, kEmpty);
  }
  cells_[cellIndex(block, x, y, z)] = value;
}

}  // namespace binpick::estimation
