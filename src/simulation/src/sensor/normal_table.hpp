#pragma once
// Internal: standard normal numbers by table lookup, for the tens of millions of noise samples of
// a capture (Box-Muller's log and cosine would dominate the rendering time). Thread-safe.
#include <cstdint>

namespace binpick::simulation::detail {

// The quantile of N(0, 1) at (k + 0.5) / 2^16 for the top 16 bits k of `bits`: exact in
// distribution up to that resolution, tails cut at about 4.3 sigma (camera noise has no use for
// rarer events).
double tabulatedStandardNormal(uint64_t bits);

}  // namespace binpick::simulation::detail
