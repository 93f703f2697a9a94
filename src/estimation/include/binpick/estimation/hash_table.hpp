#pragma once
// The model's point pair feature table (section II-A): every ordered pair of model points,
// grouped by quantised feature. Stored flat (offsets + entries) so that it is compact, fast to
// look up and can be written to a cache file as is. Immutable after construction: thread-safe.
#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "binpick/estimation/ppf.hpp"

namespace binpick::estimation {

struct PairEntry {
  uint32_t reference = 0;     // index of the model reference point m_i
  float reference_angle = 0;  // planarAngle(T_m m_j): alpha_m of the pair
};

// A read-only run of T that lies in memory someone else keeps: the table's own arrays or a mapped
// cache file.
template <class T>
struct ArrayView {
  const T* data = nullptr;
  std::size_t count = 0;
  const T* begin() const { return data; }
  const T* end() const { return data + count; }
  std::size_t size() const { return count; }
  bool empty() const { return count == 0; }
  const T& operator[](std::size_t i) const { return data[i]; }
  bool operator==(const ArrayView& other) const { return std::equal(begin(), end(), other.begin(), other.end()); }
};

class PpfHashTable {
 public:
  PpfHashTable() = default;
  // Hashes the ordered pairs (i != j) of the model points (eq. 1) whose reference i is one of the
  // first `reference_count` points (all of them: 0), the points of one turn of a symmetric part
  // (PreparedModel::reference_count). With max_pairs_per_key > 0, a key holding more pairs keeps
  // that many, spread evenly over them (flat parts crowd a few keys with near-identical pairs, and
  // every scene pair landing there votes for all of them).
  PpfHashTable(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
               const PpfQuantizer& quantizer, uint32_t max_pairs_per_key = 0, std::size_t reference_count = 0);
  // Surface-to-boundary pairs (Choi et al. 2012): each of the first `reference_count` model points
  // with its normal as the reference, every boundary point with its line direction as the referred
  // point (computeBoundaryFeature); the same cap.
  PpfHashTable(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
               const std::vector<Eigen::Vector3f>& boundary_points,
               const std::vector<Eigen::Vector3f>& boundary_directions, const PpfQuantizer& quantizer,
               uint32_t max_pairs_per_key = 0, std::size_t reference_count = 0);
  // Adopts arrays, or views arrays that `storage` keeps alive (a mapped cache file, which is then
  // neither read nor copied); validates their consistency with `reference_count` model references
  // (throws core::Error).
  PpfHashTable(std::vector<uint32_t> offsets, std::vector<PairEntry> entries, uint32_t reference_count);
  PpfHashTable(std::shared_ptr<const void> storage, ArrayView<uint32_t> offsets, ArrayView<PairEntry> entries,
               uint32_t reference_count);

  struct Range {
    const PairEntry* begin;
    const PairEntry* end;
  };
  Range lookup(int64_t key) const {
    if (key < 0 || key + 1 >= static_cast<int64_t>(offsets_.size())) return {nullptr, nullptr};
    const PairEntry* base = entries_.data;
    return {base + offsets_[key], base + offsets_[key + 1]};
  }

  const ArrayView<uint32_t>& offsets() const { return offsets_; }
  const ArrayView<PairEntry>& entries() const { return entries_; }
  std::size_t pairCount() const { return entries_.size(); }

 private:
  // Fills the table from every (reference, referred) pair that `pairKey` gives a key (-1: none),
  // the references being the first `reference_count` points.
  template <class PairKey>
  void build(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
             std::size_t reference_count, const std::vector<Eigen::Vector3f>& referred, const PpfQuantizer& quantizer,
             uint32_t max_pairs_per_key, PairKey&& pairKey);

  struct Arrays {
    std::vector<uint32_t> offsets;
    std::vector<PairEntry> entries;
  };
  void adopt(Arrays arrays);
  void validate(uint32_t reference_count) const;

  std::shared_ptr<const void> storage_;  // owns what the views point into; shared by copies
  ArrayView<uint32_t> offsets_;          // keyCount + 1 prefix sums
  ArrayView<PairEntry> entries_;
};

}  // namespace binpick::estimation
