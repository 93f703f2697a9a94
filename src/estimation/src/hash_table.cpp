#include "binpick/estimation/hash_table.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "binpick/core/error.hpp"

namespace binpick::estimation {

template <class PairKey>
void PpfHashTable::build(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
                         std::size_t reference_count, const std::vector<Eigen::Vector3f>& referred,
                         const PpfQuantizer& quantizer, uint32_t max_pairs_per_key, PairKey&& pairKey) {
  if (points.size() != normals.size()) throw core::Error("PPF table: points and normals differ in count");
  const std::size_t n = reference_count == 0 ? points.size() : std::min(reference_count, points.size());
  const std::size_t m = referred.size();
  std::vector<Eigen::Isometry3f> frames(n);
  for (std::size_t i = 0; i < n; ++i) frames[i] = referenceFrame(points[i], normals[i]);

  // Two passes (count, then fill) build the flat layout without a temporary per-key vector;
  // features are computed twice rather than stored, so memory stays O(keys + pairs).
  std::vector<uint32_t> counts(static_cast<std::size_t>(quantizer.keyCount()), 0);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < m; ++j) {
      const int64_t key = pairKey(i, j);
      if (key >= 0) ++counts[key];
    }
  }
  const auto keptOf = [&](uint32_t count) {
    return max_pairs_per_key > 0 && count > max_pairs_per_key ? max_pairs_per_key : count;
  };
  Arrays arrays;
  std::vector<uint32_t>& offsets = arrays.offsets;
  std::vector<PairEntry>& entries = arrays.entries;
  offsets.assign(counts.size() + 1, 0);
  for (std::size_t k = 0; k < counts.size(); ++k) offsets[k + 1] = offsets[k] + keptOf(counts[k]);
  entries.resize(offsets.back());
  std::vector<uint32_t> seen(counts.size(), 0);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < m; ++j) {
      const int64_t key = pairKey(i, j);
      if (key < 0) continue;
      // The a-th of `count` arrivals is kept when it starts a new one of `kept` even strides.
      const uint64_t a = seen[key]++, count = counts[key], kept = keptOf(counts[key]);
      if ((a + 1) * kept / count == a * kept / count) continue;
      entries[offsets[key] + a * kept / count] = {static_cast<uint32_t>(i), planarAngle(frames[i] * referred[j])};
    }
  }
  adopt(std::move(arrays));
}

void PpfHashTable::adopt(Arrays arrays) {
  auto owned = std::make_shared<const Arrays>(std::move(arrays));
  offsets_ = {owned->offsets.data(), owned->offsets.size()};
  entries_ = {owned->entries.data(), owned->entries.size()};
  storage_ = std::move(owned);
}

PpfHashTable::PpfHashTable(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
                           const PpfQuantizer& quantizer, uint32_t max_pairs_per_key, std::size_t reference_count) {
  build(points, normals, reference_count, points, quantizer, max_pairs_per_key,
        [&](std::size_t i, std::size_t j) -> int64_t {
          return i == j ? -1 : quantizer.pairKey(points[i], normals[i], points[j], normals[j]);
        });
}

PpfHashTable::PpfHashTable(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
                           const std::vector<Eigen::Vector3f>& boundary_points,
                           const std::vector<Eigen::Vector3f>& boundary_directions, const PpfQuantizer& quantizer,
                           uint32_t max_pairs_per_key, std::size_t reference_count) {
  if (boundary_points.size() != boundary_directions.size()) {
    throw core::Error("PPF table: boundary points and directions differ in count");
  }
  build(points, normals, reference_count, boundary_points, quantizer, max_pairs_per_key,
        [&](std::size_t i, std::size_t j) {
          return quantizer.boundaryPairKey(points[i], normals[i], boundary_points[j], boundary_directions[j]);
        });
}

PpfHashTable::PpfHashTable(std::vector<uint32_t> offsets, std::vector<PairEntry> entries, uint32_t reference_count) {
  adopt({std::move(offsets), std::move(entries)});
  validate(reference_count);
}

PpfHashTable::PpfHashTable(std::shared_ptr<const void> storage, ArrayView<uint32_t> offsets,
                           ArrayView<PairEntry> entries, uint32_t reference_count)
    : storage_(std::move(storage)), offsets_(offsets), entries_(entries) {
  validate(reference_count);
}

void PpfHashTable::validate(uint32_t reference_count) const {
  if (offsets_.empty() || offsets_[0] != 0 || offsets_[offsets_.size() - 1] != entries_.size()) {
    throw core::Error("PPF table: offsets do not cover the entries");
  }
  for (std::size_t k = 1; k < offsets_.size(); ++k) {
    if (offsets_[k] < offsets_[k - 1]) throw core::Error("PPF table: offsets decrease at key " + std::to_string(k));
  }
  for (const PairEntry& e : entries_) {
    if (e.reference >= reference_count || !std::isfinite(e.reference_angle)) {
      throw core::Error("PPF table: an entry refers to model reference " + std::to_string(e.reference) + " of " +
                        std::to_string(reference_count) + " or has a non-finite angle");
    }
  }
}

}  // namespace binpick::estimation
