#include "neighbour_grid.hpp"

#include <algorithm>

namespace binpick::estimation {

NeighbourGrid::NeighbourGrid(const std::vector<Eigen::Vector3f>& points, const std::vector<uint32_t>& members,
                             float cell_size)
    : cell_size_(cell_size) {
  if (!members.empty()) {
    origin_ = points[members.front()];
    for (uint32_t i : members) origin_ = origin_.cwiseMin(points[i]);
  }
  std::vector<std::pair<uint64_t, uint32_t>> keyed;
  keyed.reserve(members.size());
  for (uint32_t i : members) keyed.emplace_back(packCell(cellOf(points[i], origin_, cell_size_)), i);
  std::sort(keyed.begin(), keyed.end());
  sorted_.reserve(keyed.size());
  for (std::size_t k = 0; k < keyed.size(); ++k) {
    sorted_.push_back(keyed[k].second);
    auto [it, inserted] = cells_.try_emplace(keyed[k].first, static_cast<uint32_t>(k), static_cast<uint32_t>(k));
    (void)inserted;
    it->second.second = static_cast<uint32_t>(k + 1);
  }
}

}  // namespace binpick::estimation
