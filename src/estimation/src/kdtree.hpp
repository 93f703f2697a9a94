#pragma once
// Internal: a 3-D kd-tree over a vector of points (nanoflann). Queries are const and may run
// from many threads at once; the points must outlive the tree and not change.
#include <nanoflann.hpp>

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace binpick::estimation {

class KdTree {
 public:
  explicit KdTree(const std::vector<Eigen::Vector3f>& points)
      : adaptor_{points}, index_(3, adaptor_, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {}

  // Index of the nearest point and its squared distance; {-1, inf} for an empty tree.
  std::pair<int, float> nearest(const Eigen::Vector3f& query) const {
    uint32_t index = 0;
    float distance_sq = std::numeric_limits<float>::infinity();
    if (adaptor_.points.empty() || index_.knnSearch(query.data(), 1, &index, &distance_sq) == 0) {
      return {-1, std::numeric_limits<float>::infinity()};
    }
    return {static_cast<int>(index), distance_sq};
  }

  // As nearest(), among the points within sqrt(max_distance_sq) of the query only: the bound prunes
  // the search from the start, so a query with nothing near returns at once. ICP's correspondence
  // gate is such a bound.
  std::pair<int, float> nearestWithin(const Eigen::Vector3f& query, float max_distance_sq) const {
    NearestWithin result(max_distance_sq);
    if (!adaptor_.points.empty()) index_.findNeighbors(result, query.data(), nanoflann::SearchParams());
    if (result.index < 0) return {-1, std::numeric_limits<float>::infinity()};
    return {result.index, result.distance_sq};
  }

  // Squared distance from the point at `index` to its nearest other point; inf when it has none.
  float nearestOtherSq(uint32_t index) const {
    uint32_t found[2] = {0, 0};
    float distance_sq[2] = {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity()};
    const std::size_t n = index_.knnSearch(adaptor_.points[index].data(), 2, found, distance_sq);
    return n == 2 ? distance_sq[1] : std::numeric_limits<float>::infinity();
  }

  // Indices of all points within `radius` (unsorted), written to `out`.
  void withinRadius(const Eigen::Vector3f& query, float radius, std::vector<uint32_t>& out) const {
    matches_buffer().clear();
    nanoflann::SearchParams params;
    params.sorted = false;
    index_.radiusSearch(query.data(), radius * radius, matches_buffer(), params);
    out.clear();
    for (const auto& match : matches_buffer()) out.push_back(match.first);
  }

 private:
  struct Adaptor {
    const std::vector<Eigen::Vector3f>& points;
    std::size_t kdtree_get_point_count() const { return points.size(); }
    float kdtree_get_pt(std::size_t i, std::size_t dim) const { return points[i][static_cast<int>(dim)]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
      return false;
    }
  };
  // nanoflann's result-set interface for one nearest point under a bound (inclusive, as
  // `distance_sq <= bound` after nearest() was).
  struct NearestWithin {
    explicit NearestWithin(float max_distance_sq)
        : distance_sq(std::nextafter(max_distance_sq, std::numeric_limits<float>::infinity())) {}
    bool full() const { return true; }
    bool addPoint(float candidate_sq, uint32_t candidate) {
      if (candidate_sq < distance_sq) distance_sq = candidate_sq, index = static_cast<int>(candidate);
      return true;
    }
    float worstDist() const { return distance_sq; }
    float distance_sq;
    int index = -1;
  };
  using Index = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Adaptor>, Adaptor, 3, uint32_t>;
  static std::vector<std::pair<uint32_t, float>>& matches_buffer() {
    thread_local std::vector<std::pair<uint32_t, float>> buffer;
    return buffer;
  }

  Adaptor adaptor_;
  Index index_;
};

}  // namespace binpick::estimation
