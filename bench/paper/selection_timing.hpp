#pragma once
// The paper's Figure 5: how the time of multiple selection grows with the number of detections.
// On one scene's verified candidates, three ways to pick the best remaining pose again and again
// while the picked poses' scene points stop existing:
// - Algorithm 1 (binpick): candidates refreshed with eq. 4 in the order of their old scores, until
//   none below can win;
// - eq. 4 for every candidate after each pick (stored SS(P_k), no early stop);
// - every candidate verified again after each pick (its model points looked up in the voxel grid
//   again, then eq. 4): what re-verifying methods such as CSF pay.
// All three pick the same poses; only the work differs. ICP is left out: this times selection.
#include <cstdint>
#include <vector>

#include "binpick/estimation/model.hpp"
#include "scene.hpp"
#include "binpick/io/point_cloud.hpp"

namespace binpick::bench {

struct SelectionCurves {
  std::size_t scene_points = 0, candidates = 0;
  // Cumulative milliseconds after the k-th pick (index k - 1), one entry per pick made.
  std::vector<double> algorithm1_ms, rescore_all_ms, reverify_all_ms;
  // The candidate picked each time, per strategy (they must agree).
  std::vector<uint32_t> algorithm1_picks, rescore_all_picks, reverify_all_picks;
};

// One thread for the selection strategies (Algorithm 1 is sequential); voting and verification
// use `threads` (0: all).
SelectionCurves measureSelection(const estimation::PreparedModel& model, const io::PointCloud& cloud,
                                 const estimation::CropBox& crop, int picks, int threads);

}  // namespace binpick::bench
