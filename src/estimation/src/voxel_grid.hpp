#pragma once
// The scene voxel grid of the verification (section III-C, eq. 3): cubic voxels of side L_voxel
// over the scene's bounding box; each scene point writes its index into its own voxel and the 26
// neighbours, so a lookup answers "which scene point is near here" in O(1). Voxels are stored in
// 8x8x8 blocks allocated only where the scene has points: a bin scene is a 2.5-D surface, and a
// dense grid over its box would cost hundreds of MB. Immutable after construction: thread-safe.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace binpick::estimation {

class SceneVoxelGrid {
 public:
  static constexpr int32_t kEmpty = -1;

  // Throws core::Error on a non-positive voxel size or a non-finite scene point.
  SceneVoxelGrid(const std::vector<Eigen::Vector3f>& scene_points, float voxel_size);

  // Voxel(p) of eq. 3: the index of a scene point near p, or kEmpty.
  int32_t at(const Eigen::Vector3f& p) const { return atVoxelCoordinates((p - origin_) / voxel_size_); }

  // The map of a pose's model frame into voxel coordinates: at(pose * m) is
  // atVoxelCoordinates(map * m), but for rounding at a voxel's border. Verification looks up every
  // model point of thousands of poses; with the origin and the scale folded into the pose, a
  // lookup costs one affine map instead of a map, a subtraction and three divisions.
  Eigen::Affine3f voxelMapOf(const Eigen::Isometry3f& pose) const {
    Eigen::Affine3f map;
    map.linear() = pose.linear() / voxel_size_;
    map.translation() = (pose.translation() - origin_) / voxel_size_;
    return map;
  }

  // The index of a scene point near the point at voxel coordinates q, or kEmpty.
  int32_t atVoxelCoordinates(const Eigen::Vector3f& q) const {
    // Compared as floats before the cast: NaN, infinities and huge values never reach an index.
    if (!(q.x() >= 0.0f && q.y() >= 0.0f && q.z() >= 0.0f && q.x() < dims_f_.x() && q.y() < dims_f_.y() &&
          q.z() < dims_f_.z())) {
      return kEmpty;
    }
    const auto x = static_cast<int64_t>(q.x()), y = static_cast<int64_t>(q.y()), z = static_cast<int64_t>(q.z());
    const int32_t block = blocks_[blockIndex(x >> 3, y >> 3, z >> 3)];
    if (block < 0) return kEmpty;
    return cells_[cellIndex(block, x, y, z)];
  }

  float voxelSize() const { return voxel_size_; }

 private:
  // Voxel (x, y, z) inside its 8x8x8 block.
  static std::size_t cellIndex(int32_t block, int64_t x, int64_t y, int64_t z) {
    return static_cast<std::size_t>(block) * 512 + static_cast<std::size_t>((z & 7) << 6 | (y & 7) << 3 | (x & 7));
  }
  std::size_t blockIndex(int64_t bx, int64_t by, int64_t bz) const {
    return static_cast<std::size_t>((bz * block_dims_.y() + by) * block_dims_.x() + bx);
  }
  void write(int64_t x, int64_t y, int64_t z, int32_t value);

  Eigen::Vector3f origin_ = Eigen::Vector3f::Zero();
  float voxel_size_;
  Eigen::Matrix<int64_t, 3, 1> dims_ = Eigen::Matrix<int64_t, 3, 1>::Zero();
  Eigen::Vector3f dims_f_ = Eigen::Vector3f::Zero();
  Eigen::Matrix<int64_t, 3, 1> block_dims_ = Eigen::Matrix<int64_t, 3, 1>::Zero();
  std::vector<int32_t> blocks_;  // per block: index into cells_ / 512, or -1
  std::vector<int32_t> cells_;
};

}  // namespace binpick::estimation
