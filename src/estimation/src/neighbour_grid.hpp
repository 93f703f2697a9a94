#pragma once
// Internal: uniform grid for "all points within r" queries when r is large compared with the
// point spacing (the voting's referred points lie within diam(M) of the reference: a kd-tree
// would visit most of its nodes). Immutable after construction: thread-safe.
#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "cell_key.hpp"

namespace binpick::estimation {

class NeighbourGrid {
 public:
  NeighbourGrid(const std::vector<Eigen::Vector3f>& points, const std::vector<uint32_t>& members, float cell_size);

  // Calls visit(index) for every member in the 3x3x3 cells around p: a superset of the members
  // within cell_size of p (callers check the exact distance).
  template <class Visit>
  void forEachNear(const Eigen::Vector3f& p, Visit&& visit) const {
    const Eigen::Vector3i c = cellOf(p, origin_, cell_size_);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = cells_.find(packCell(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (uint32_t k = it->second.first; k < it->second.second; ++k) visit(sorted_[k]);
        }
  }

 private:
  Eigen::Vector3f origin_ = Eigen::Vector3f::Zero();
  float cell_size_;
  std::vector<uint32_t> sorted_;
  std::unordered_map<uint64_t, std::pair<uint32_t, uint32_t>> cells_;
};

}  // namespace binpick::estimation
