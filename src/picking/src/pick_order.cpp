#include "pick_order.hpp"

#include <algorithm>
#include <tuple>

namespace binpick::picking {

void sortPicks(std::vector<Pick>& picks, const std::vector<DetectedPart>& parts, PickOrder order) {
  const auto height = [](const Pick& pick) { return pick.T_base_grasp.translation().z(); };
  const auto score = [&parts](const Pick& pick) { return parts[static_cast<std::size_t>(pick.object)].score; };
  const auto unsure = [&parts](const Pick& pick) { return !parts[static_cast<std::size_t>(pick.object)].sure; };
  // Tuples compare key by key; negating height and score makes them descend, and false (sure)
  // comes before true. The explicit orders keep their one key: only the rank is the planner's own
  // judgement, which the detector's doubt should outweigh.
  const auto sortKey = [&](const Pick& pick) {
    switch (order) {
      case PickOrder::HighestFirst: return std::make_tuple(false, -height(pick), -score(pick), pick.object);
      case PickOrder::BestScore: return std::make_tuple(false, -score(pick), -height(pick), pick.object);
      case PickOrder::BestRank: break;
    }
    return std::make_tuple(unsure(pick), -pick.rank, -height(pick), pick.object);
  };
  std::sort(picks.begin(), picks.end(), [&](const Pick& a, const Pick& b) { return sortKey(a) < sortKey(b); });
}

}  // namespace binpick::picking
