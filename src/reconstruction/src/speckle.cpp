// Speckle detection: runs of connected pixels along each row, joined across rows by union-find.
#include "speckle.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace binpick::reconstruction::detail {
namespace {

// Disjoint sets over runs, by size, with path halving.
class RunSets {
 public:
  RunSets() = default;
  // The sets of several bands in one, their runs numbered one band after the other.
  explicit RunSets(std::vector<RunSets>& bands) {
    for (RunSets& band : bands) {
      const auto offset = static_cast<int32_t>(parent_.size());
      for (int32_t run = 0; run < band.count(); ++run) {
        parent_.push_back(offset + band.find(run));
        size_.push_back(band.size_[run]);
      }
    }
  }
  int32_t add(int32_t pixels) {
    parent_.push_back(static_cast<int32_t>(parent_.size()));
    size_.push_back(pixels);
    return parent_.back();
  }
  int32_t find(int32_t run) {
    while (parent_[run] != run) {
      parent_[run] = parent_[parent_[run]];
      run = parent_[run];
    }
    return run;
  }
  void join(int32_t a, int32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
  }
  int32_t size(int32_t root) const { return size_[root]; }
  int32_t count() const { return static_cast<int32_t>(parent_.size()); }

 private:
  std::vector<int32_t> parent_;
  std::vector<int32_t> size_;
};

// Points i and j of the cloud, neighbours, are one surface.
bool connected(const io::PointCloud& cloud, std::size_t i, std::size_t j, const DepthStep& step) {
  return std::abs(cloud.points[i].z() - cloud.points[j].z()) <= step.between(i, j);  // NaN: no
}

// Labels one row's runs: consecutive points (organized clouds mark missing ones with NaN), each
// within the step of its left neighbour.
void labelRow(const io::PointCloud& cloud, int y, const DepthStep& step, RunSets& sets, int32_t* labels) {
  const int width = cloud.width;
  const std::size_t first = static_cast<std::size_t>(y) * width;
  const Eigen::Vector3f* points = cloud.points.data() + first;
  int x = 0;
  while (x < width) {
    if (std::isnan(points[x].z())) {
      labels[x++] = -1;
      continue;
    }
    const int start = x++;
    while (x < width && connected(cloud, first + x, first + x - 1, step)) ++x;
    std::fill(labels + start, labels + x, sets.add(x - start));
  }
}

// Joins the runs of row y with those of row y - 1 wherever vertical neighbours connect.
void joinRows(const io::PointCloud& cloud, int y, const DepthStep& step, RunSets& sets, const int32_t* above,
              const int32_t* labels) {
  const int width = cloud.width;
  const std::size_t first = static_cast<std::size_t>(y) * width;
  int32_t last_above = -1, last = -1;  // the pair joined last: runs overlap over many pixels
  for (int x = 0; x < width; ++x) {
    if (labels[x] < 0 || above[x] < 0) continue;
    if (labels[x] == last && above[x] == last_above) continue;
    if (!connected(cloud, first + x, first + x - width, step)) continue;
    sets.join(labels[x], above[x]);
    last = labels[x];
    last_above = above[x];
  }
}

}  // namespace

std::vector<uint8_t> findSpeckles(const io::PointCloud& cloud, const DepthStep& step, int min_pixels, int threads) {
  const std::size_t count = cloud.points.size();
  const int width = cloud.width;
  std::vector<int32_t> labels(count, -1);
  // Bands of rows are labelled in parallel, each with its own sets; then the sets are merged and
  // the bands joined along their first rows.
  const int bands = std::max(1, std::min(threads, cloud.height));
  std::vector<RunSets> band_sets(bands);
  std::vector<int> first_row(bands + 1);
  for (int b = 0; b <= bands; ++b) first_row[b] = static_cast<int>(static_cast<long>(cloud.height) * b / bands);
#pragma omp parallel for num_threads(bands) schedule(static, 1)
  for (int b = 0; b < bands; ++b) {
    for (int y = first_row[b]; y < first_row[b + 1]; ++y) {
      int32_t* row_labels = labels.data() + static_cast<std::size_t>(y) * width;
      labelRow(cloud, y, step, band_sets[b], row_labels);
      if (y > first_row[b]) joinRows(cloud, y, step, band_sets[b], row_labels - width, row_labels);
    }
  }
  std::vector<int32_t> offset(bands, 0);
  for (int b = 1; b < bands; ++b) offset[b] = offset[b - 1] + band_sets[b - 1].count();
#pragma omp parallel for num_threads(bands) schedule(static, 1)
  for (int b = 1; b < bands; ++b) {
    const auto begin = labels.begin() + static_cast<std::ptrdiff_t>(first_row[b]) * width;
    const auto end = labels.begin() + static_cast<std::ptrdiff_t>(first_row[b + 1]) * width;
    for (auto label = begin; label != end; ++label) {
      if (*label >= 0) *label += offset[b];
    }
  }
  RunSets sets(band_sets);
  for (int b = 1; b < bands; ++b) {
    const int32_t* row_labels = labels.data() + static_cast<std::size_t>(first_row[b]) * width;
    joinRows(cloud, first_row[b], step, sets, row_labels - width, row_labels);
  }
  // Decided per run, then spread to the pixels: runs are far fewer.
  std::vector<uint8_t> small_run(sets.count());
  for (int32_t run = 0; run < sets.count(); ++run) {
    small_run[run] = sets.size(sets.find(run)) < min_pixels ? 1 : 0;
  }
  std::vector<uint8_t> speckle(count, 0);
#pragma omp parallel for num_threads(bands) schedule(static)
  for (long i = 0; i < static_cast<long>(count); ++i) {
    if (labels[i] >= 0) speckle[i] = small_run[labels[i]];
  }
  return speckle;
}

}  // namespace binpick::reconstruction::detail
