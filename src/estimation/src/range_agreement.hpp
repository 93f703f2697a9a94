#pragma once
// How a posed part agrees with what the camera measured, point by point along each line of sight.
// A part lying on one face shows nearly the same surface in a pose and in its turned twin (a
// housing with its profile mirrored, a bracket turned over); they differ only near the outline,
// by a few millimetres, where one pose has material and the other has none. The subsampled fit
// (nearest scene point within a step) cannot see that: its own sampling noise is larger. Here the
// model's fine surface (half a step apart) is compared with the line-of-sight map (the nearest
// depth measured per viewing direction, from the full-resolution cloud): a visible model point is
// explained when the measured depth is within the tolerance, seen through when the camera measured
// something farther (nothing was there), and hidden when something nearer was measured (an
// occluder: no evidence either way). Thread-safe (no shared state).
#include <Eigen/Geometry>

#include "binpick/estimation/model.hpp"
#include "line_of_sight.hpp"

namespace binpick::estimation {

struct RangeAgreement {
  int visible = 0;       // fine model points the camera would measure (facing it, not grazing)
  int explained = 0;     // ... with the measured depth within the tolerance
  int seen_through = 0;  // ... lying in front of the measured depth (the camera saw past them)
  int hidden = 0;        // ... lying behind it (something nearer hides them)
  int unseen = 0;        // ... where nothing was measured (shadow, hole)
  int consistency() const { return explained - seen_through; }
};

// The model's fine surface at `pose` against `map`; `tolerance` in model units.
RangeAgreement rangeAgreement(const PreparedModel& model, const Eigen::Isometry3f& pose, const LineOfSightMap& map,
                              float tolerance);

}  // namespace binpick::estimation
