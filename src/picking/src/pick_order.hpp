#pragma once
// The order the robot takes the picks in.
#include <vector>

#include "binpick/picking/picking.hpp"

namespace binpick::picking {

// Sorts `picks` by PickParams::order (picking.hpp): deterministic, every tie broken down to the
// object index. `parts` supplies the scores and whether each is sure (Pick::object indexes it;
// scores finite).
void sortPicks(std::vector<Pick>& picks, const std::vector<DetectedPart>& parts, PickOrder order);

}  // namespace binpick::picking
