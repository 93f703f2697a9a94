#pragma once
// The model's point pair feature table (section II-A): every ordered pair of model points,
// grouped by quantised feature. Stored flat (offsets + entries) so that it is compact, fast to
// look up and can be written to a cache file as is. Immutable after construction: thread-safe.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "binpick/estimation/ppf.hpp"

namespace binpick::estimation {

struct PairEntry {
  uint32_t reference = 0;     // index of the model reference point m_i
  float reference_angle = 0;  // planarAngle(T_m m_j): alpha_m of the pair
};

class PpfHashTable {
 public:
  PpfHashTable() = default;
  // Hashes all ordered pairs (i != j) of the model points (eq. 1). With max_pairs_per_key > 0, a
  // key holding more pairs keeps that many, spread evenly over them (flat parts crowd a few keys
  // with near-identical pairs, and every scene pair landing there votes for all of them).
  PpfHashTable(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
               const PpfQuantizer& quantizer, uint32_t max_pairs_per_key = 0);
  // Surface-to-boundary pairs (Choi et al. 2012): every model point with its normal as the
  // reference, every boundary point with its line direction as the referred point
  // (computeBoundaryFeature); the same cap.
  PpfHashTable(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
               const std::vector<Eigen::Vector3f>& boundary_points,
               const std::vector<Eigen::Vector3f>& boundary_directions, const PpfQuantizer& quantizer,
               uint32_t max_pairs_per_key = 0);
  // Adopts arrays read from a cache; validates their consistency (throws core::Error).
  PpfHashTable(std::vector<uint32_t> offsets, std::vector<PairEntry> entries, uint32_t point_count);

  struct Range {
    const PairEntry* begin;
    const PairEntry* end;
  };
  Range lookup(int64_t key) const {
    if (key < 0 || key + 1 >= static_cast<int64_t>(offsets_.size())) return {nullptr, nullptr};
    const PairEntry* base = entries_.data();
    return {base + offsets_[key], base + offsets_[key + 1]};
  }

  const std::vector<uint32_t>& offsets() const { return offsets_; }
  const std::vector<PairEntry>& entries() const { return entries_; }
  std::size_t pairCount() const { return entries_.size(); }

 private:
  // Fills the table from every (reference, referred) pair that `pairKey` gives a key (-1: none).
  template <class PairKey>
  void build(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
             const std::vector<Eigen::Vector3f>& referred, const PpfQuantizer& quantizer, uint32_t max_pairs_per_key,
             PairKey&& pairKey);

  std::vector<uint32_t> offsets_;  // keyCount + 1 prefix sums
  std::vector<PairEntry> entries_;
};

}  // namespace binpick::estimation
