#include "piece_merging.hpp"

#include <algorithm>
#include <optional>

#include "hull_fit.hpp"

namespace binpick::simulation::detail {
namespace {

struct JoinCandidate {
  int a = 0, b = 0;  // slots
  ConvexHull joint;
  double added = 0.0;  // joint volume beyond the two pieces'
  std::optional<bool> fits;
};

class Merger {
 public:
  Merger(std::vector<ConvexHull> pieces, const SolidGrid& solid) : solid_(solid) {
    for (auto& piece : pieces) slots_.emplace_back(std::move(piece));
    for (int slot = 0; slot < static_cast<int>(slots_.size()); ++slot) addCandidates(slot, true);
  }

  int count() const {
    return static_cast<int>(std::count_if(slots_.begin(), slots_.end(), [](const auto& s) { return s.has_value(); }));
  }

  // Joins the cheapest pair whose joint hull fits; false when none does.
  bool joinCheapestFitting() {
    sortCandidates();
    for (auto& candidate : candidates_) {
      if (!candidate.fits) candidate.fits = hullFits(solid_, candidate.joint);
      if (*candidate.fits) {
        join(candidate);
        return true;
      }
    }
    return false;
  }

  // Joins the cheapest pair of neighbours, or of any two pieces if none touch.
  void joinCheapest() {
    if (candidates_.empty()) {
      for (int slot = 0; slot < static_cast<int>(slots_.size()); ++slot) addCandidates(slot, false);
    }
    sortCandidates();
    join(candidates_.front());
  }

  std::vector<ConvexHull> pieces() && {
    std::vector<ConvexHull> out;
    for (auto& slot : slots_)
      if (slot) out.push_back(std::move(*slot));
    return out;
  }

 private:
  bool touching(const ConvexHull& p, const ConvexHull& q) const {
    const double gap = solid_.grid().cell_size;
    Eigen::AlignedBox3d grown = p.box;
    grown.min().array() -= gap;
    grown.max().array() += gap;
    return grown.intersects(q.box);
  }

  // Pairs of `slot` with the live slots before it.
  void addCandidates(int slot, bool neighbours_only) {
    for (int other = 0; other < slot; ++other) {
      if (!slots_[other] || (neighbours_only && !touching(*slots_[other], *slots_[slot]))) continue;
      JoinCandidate candidate;
      candidate.a = other;
      candidate.b = slot;
      std::vector<Eigen::Vector3d> points = slots_[other]->vertices;
      points.insert(points.end(), slots_[slot]->vertices.begin(), slots_[slot]->vertices.end());
      candidate.joint = convexHull(points);
      candidate.added = candidate.joint.volume - slots_[other]->volume - slots_[slot]->volume;
      candidates_.push_back(std::move(candidate));
    }
  }

  void sortCandidates() {
    std::stable_sort(candidates_.begin(), candidates_.end(),
                     [](const JoinCandidate& p, const JoinCandidate& q) { return p.added < q.added; });
  }

  void join(JoinCandidate candidate) {
    const int a = candidate.a, b = candidate.b;
    slots_[a].reset();
    slots_[b].reset();
    candidates_.erase(
        std::remove_if(candidates_.begin(), candidates_.end(),
                       [&](const JoinCandidate& c) { return c.a == a || c.a == b || c.b == a || c.b == b; }),
        candidates_.end());
    slots_.emplace_back(std::move(candidate.joint));
    addCandidates(static_cast<int>(slots_.size()) - 1, true);
  }

  const SolidGrid& solid_;
  std::vector<std::optional<ConvexHull>> slots_;
  std::vector<JoinCandidate> candidates_;
};

}  // namespace

std::vector<ConvexHull> mergePieces(std::vector<ConvexHull> pieces, const SolidGrid& solid, int max_pieces) {
  Merger merger(std::move(pieces), solid);
  while (merger.joinCheapestFitting()) {
  }
  while (merger.count() > max_pieces) merger.joinCheapest();
  return std::move(merger).pieces();
}

}  // namespace binpick::simulation::detail
