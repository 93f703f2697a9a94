#pragma once
// Internal: integer cells of a uniform grid and their packed 64-bit keys, shared by the voxel
// subsampling and the neighbour grid.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>

namespace binpick::estimation {

constexpr int kCellBits = 21;
constexpr int kCellLimit = 1 << (kCellBits - 1);  // cells from -kCellLimit to kCellLimit - 1

// Cell of p on a grid of side `size` starting at `origin`, clamped into the packable range in
// float before the conversion, so far or huge coordinates never overflow it.
inline Eigen::Vector3i cellOf(const Eigen::Vector3f& p, const Eigen::Vector3f& origin, float size) {
  Eigen::Vector3i cell;
  for (int a = 0; a < 3; ++a) {
    const float q = std::floor((p[a] - origin[a]) / size);
    cell[a] = q < -kCellLimit ? -kCellLimit : (q > kCellLimit - 1 ? kCellLimit - 1 : static_cast<int>(q));
  }
  return cell;
}

// 21 bits per axis.
inline uint64_t packCell(const Eigen::Vector3i& c) {
  const auto part = [](int v) { return static_cast<uint64_t>(v + kCellLimit) & ((uint64_t{1} << kCellBits) - 1); };
  return part(c.x()) | (part(c.y()) << kCellBits) | (part(c.z()) << (2 * kCellBits));
}

}  // namespace binpick::estimation
