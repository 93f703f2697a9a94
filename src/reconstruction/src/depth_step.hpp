#pragma once
// How far apart in camera z two neighbouring points of one surface may be, for the filters that
// grow or check surfaces from neighbours (speckle.hpp, depth_edges.hpp).
#include <algorithm>
#include <cstddef>

namespace binpick::reconstruction::detail {

// A fixed step (metres, or a share of z), raised per point where the decoding itself is coarser:
// a capture without phase images is decoded to whole codes, and neighbours on one smooth surface
// are a code apart, which spans centimetres of depth for a rig metres away (and a fraction of a
// millimetre for a near one). `coarse` holds that step per point (metres; NaN: none), or is
// nullptr; a pair of points takes the larger of its two.
struct DepthStep {
  float fixed = 0.0f;
  const float* coarse = nullptr;
  // NaN coarse steps lose to the fixed one (std::max keeps its first argument then).
  float at(std::size_t i, float fixed_here) const { return coarse ? std::max(fixed_here, coarse[i]) : fixed_here; }
  float at(std::size_t i) const { return at(i, fixed); }
  float between(std::size_t i, std::size_t j) const { return std::max(at(i), at(j)); }
};

}  // namespace binpick::reconstruction::detail
