#include "cut_choice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace binpick::simulation::detail {
namespace {

constexpr int kCoarseCutsPerAxis = 8;
// Surface points per side used to compare cuts (more on a side only thin out the estimate).
constexpr std::size_t kScoringPoints = 300;
// A cut must remove at least this share of the piece's excess volume to be chosen for it. Some
// concavities need two cuts before either helps (a hole: each half of a ring still wraps half the
// hole), and then a cut that merely shaves a little off is worse than halving the piece.
constexpr double kMinExcessGain = 0.1;

// Cells along each axis that hold solid (inside or crossed by the surface): a cut must have some
// on both sides.
struct OccupiedExtent {
  Eigen::Vector3i first = Eigen::Vector3i::Constant(std::numeric_limits<int>::max());
  Eigen::Vector3i last = Eigen::Vector3i::Constant(std::numeric_limits<int>::min());
};

OccupiedExtent occupiedExtent(const SolidGrid& solid, const CellBox& box) {
  OccupiedExtent extent;
  for (int k = box.lo.z(); k < box.hi.z(); ++k)
    for (int j = box.lo.y(); j < box.hi.y(); ++j)
      for (int i = box.lo.x(); i < box.hi.x(); ++i)
        if (solid.occupied(i, j, k)) {
          extent.first = extent.first.cwiseMin(Eigen::Vector3i(i, j, k));
          extent.last = extent.last.cwiseMax(Eigen::Vector3i(i, j, k));
        }
  return extent;
}

class CutSearch {
 public:
  CutSearch(const BoxPiece& piece, const SolidGrid& solid, const MeshColumns& columns)
      : piece_(piece), solid_(solid), columns_(columns), cell_volume_(std::pow(solid.grid().cell_size, 3)) {}

  // Scores the cut at the border below cell `index` along `axis`; keeps the best so far.
  void tryCut(int axis, int index, const OccupiedExtent& extent) {
    if (index <= extent.first[axis] || index > extent.last[axis]) return;
    const SplitVolumes hulls = estimateSplitVolumes(piece_, axis, index, solid_.grid(), columns_, kScoringPoints);
    const double score = hulls.below + hulls.above - solidVolume(piece_.box);
    // Middle cuts win ties: balanced pieces make fewer, larger pieces in the end.
    const double middle = 0.5 * (extent.first[axis] + extent.last[axis] + 1);
    const double off_centre = std::abs(index - middle) / (extent.last[axis] - extent.first[axis] + 1);
    const double tie = 1e-3 * cell_volume_;
    if (!found_ || score < best_score_ - tie || (score <= best_score_ + tie && off_centre < best_off_centre_)) {
      found_ = true;
      best_score_ = score;
      best_off_centre_ = off_centre;
      best_axis_ = axis;
      best_index_ = index;
    }
  }

  bool found() const { return found_; }
  double bestScore() const { return best_score_; }
  int bestAxis() const { return best_axis_; }
  int bestIndex() const { return best_index_; }

  // The solid's volume within `box`, counted in cells.
  double solidVolume(const CellBox& box) const { return cell_volume_ * solid_.insideCells(box); }

 private:
  const BoxPiece& piece_;
  const SolidGrid& solid_;
  const MeshColumns& columns_;
  double cell_volume_;
  bool found_ = false;
  double best_score_ = 0.0, best_off_centre_ = 0.0;
  int best_axis_ = 0, best_index_ = 0;
};

}  // namespace

std::optional<BoxSplit> bestSplit(const BoxPiece& piece, const SolidGrid& solid, const MeshColumns& columns) {
  const OccupiedExtent extent = occupiedExtent(solid, piece.box);
  CutSearch search(piece, solid, columns);
  Eigen::Vector3i coarse_step = Eigen::Vector3i::Ones();
  for (int axis = 0; axis < 3; ++axis) {
    const int span = extent.last[axis] - extent.first[axis];  // possible cuts along this axis
    if (span < 1) continue;
    coarse_step[axis] = std::max(1, (span + kCoarseCutsPerAxis) / (kCoarseCutsPerAxis + 1));
    for (int index = extent.first[axis] + coarse_step[axis]; index <= extent.last[axis]; index += coarse_step[axis])
      search.tryCut(axis, index, extent);
  }
  if (!search.found()) return std::nullopt;
  // Refine around the best cut with ever finer steps (a third each time).
  const int axis = search.bestAxis();
  for (int step = coarse_step[axis]; step > 1;) {
    step = (step + 2) / 3;
    const int centre = search.bestIndex();
    for (const int k : {-2, -1, 1, 2}) search.tryCut(axis, centre + k * step, extent);
  }
  const double excess = piece.hull.volume - search.solidVolume(piece.box);
  if (search.bestScore() <= (1.0 - kMinExcessGain) * excess) {
    return splitBoxPiece(piece, axis, search.bestIndex(), solid.grid(), columns);
  }
  // Halve the piece across its longest extent instead.
  int longest = 0;
  for (int a = 1; a < 3; ++a) {
    if (extent.last[a] - extent.first[a] > extent.last[longest] - extent.first[longest]) longest = a;
  }
  const int middle = (extent.first[longest] + extent.last[longest] + 1) / 2;
  return splitBoxPiece(piece, longest, middle, solid.grid(), columns);
}

}  // namespace binpick::simulation::detail
