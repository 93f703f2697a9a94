#pragma once
// The choice between a refined pick and its twins (near_symmetries.hpp). A part showing a single
// face is explained nearly as well by the pick turned over or turned end for end: each twin that
// agrees nearly as well with the measured range is refined too, and the pose whose fine surface the
// range explains most, less what the camera saw through (range_agreement.hpp), is kept. A twin must
// win by a margin, so that noise does not swap poses that are equally good; only a `turned` twin
// may win, a `slid` one weighs on the margin (Detection::twin_margin). Thread-safe (no shared state).
#include <Eigen/Geometry>

#include "binpick/estimation/detector.hpp"
#include "binpick/estimation/near_symmetries.hpp"
#include "icp.hpp"
#include "line_of_sight.hpp"

namespace binpick::estimation {

// A pose after ICP: the detection's pose, coverage, residual and iterations, and its fit.
struct RefinedPose {
  Detection detection;
  PoseFit fit;
};
RefinedPose refinedPose(const PoseRefiner& refiner, const PreparedModel& model, const Eigen::Isometry3f& pose,
                        int max_iterations);

// What the twins are judged with: the range's line-of-sight map, the tolerance of the refined
// free-space test (model units), the pick's ICP iterations (a twin gets a third: registered onto
// the model, it starts within millimetres of its fit) and the threads the twins are refined on.
struct TwinJudging {
  const LineOfSightMap& map;
  float tolerance = 0.0f;
  int max_iterations = 0;
  int threads = 1;
};

// The pick, or the turned twin the range prefers by the margin, with its seen-through share and
// its margin over the best other pose.
Detection mostConsistent(const PoseRefiner& refiner, const PreparedModel& model, const RefinedPose& pick,
                         const NearSymmetries& twins, const TwinJudging& judging);

}  // namespace binpick::estimation
