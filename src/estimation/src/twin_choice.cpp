#include "twin_choice.hpp"

#include <algorithm>
#include <limits>
#include <vector>

#include "point_ops.hpp"
#include "range_agreement.hpp"

namespace binpick::estimation {
namespace {

// A pose with the range's judgement of it.
struct Judged {
  RefinedPose pose;
  RangeAgreement agreement;
  bool judged = false;
  int consistency() const { return judged ? agreement.consistency() : std::numeric_limits<int>::min(); }
  float seenThroughShare() const {
    return agreement.visible == 0 ? 0.0f
                                  : static_cast<float>(agreement.seen_through) / static_cast<float>(agreement.visible);
  }
};

// A twin, refined; or where it started when ICP made it agree less with the range (ICP can slide a
// part lying on one face along it, off its outline). Not judged when it agrees with the range less
// than `floor` before ICP: it could not win after.
Judged judgedTwin(const PoseRefiner& refiner, const PreparedModel& model, const Eigen::Isometry3f& turned,
                  const TwinJudging& judging, int floor) {
  Judged twin;
  const RangeAgreement start = rangeAgreement(model, turned, judging.map, judging.tolerance);
  if (start.consistency() < floor) return twin;
  twin.judged = true;
  twin.pose = refinedPose(refiner, model, turned, judging.max_iterations / 3);
  twin.agreement = rangeAgreement(model, twin.pose.detection.T_camera_model, judging.map, judging.tolerance);
  if (start.consistency() > twin.agreement.consistency()) {
    twin.pose.fit = refiner.assess(model, turned);
    twin.pose.detection.T_camera_model = turned;
    orthonormalise(twin.pose.detection.T_camera_model);
    twin.pose.detection.coverage = twin.pose.fit.coverage();
    twin.pose.detection.icp_rmse = twin.pose.fit.rmse;
    twin.agreement = start;
  }
  return twin;
}

}  // namespace

RefinedPose refinedPose(const PoseRefiner& refiner, const PreparedModel& model, const Eigen::Isometry3f& pose,
                        int max_iterations) {
  const IcpResult icp = refiner.refine(model, pose, max_iterations);
  RefinedPose r;
  r.detection.T_camera_model = icp.T_camera_model;
  r.detection.coverage = icp.fit.coverage();
  r.detection.icp_rmse = icp.fit.rmse;
  r.detection.icp_iterations = icp.iterations;
  r.fit = icp.fit;
  return r;
}

Detection mostConsistent(const PoseRefiner& refiner, const PreparedModel& model, const RefinedPose& pick,
                         const NearSymmetries& twins, const TwinJudging& judging) {
  const Judged judged_pick{pick, rangeAgreement(model, pick.detection.T_camera_model, judging.map, judging.tolerance),
                           true};
  const std::size_t turned = twins.turned.size();
  const auto turn = [&](std::size_t t) -> const Eigen::Isometry3f& {
    return t < turned ? twins.turned[t] : twins.slid[t - turned];
  };
  std::vector<Judged> judged(turned + twins.slid.size());
  // The twins are independent: judged side by side (refine() is const and thread-safe).
#pragma omp parallel for num_threads(judging.threads) schedule(dynamic, 1)
  for (std::size_t t = 0; t < judged.size(); ++t) {
    judged[t] =
        judgedTwin(refiner, model, pick.detection.T_camera_model * turn(t), judging, judged_pick.consistency() * 4 / 5);
  }
  const Judged* best = &judged_pick;
  int to_beat = judged_pick.consistency() + std::max(3, judged_pick.agreement.visible / 50);
  for (std::size_t t = 0; t < turned; ++t) {
    if (judged[t].consistency() > to_beat) best = &judged[t], to_beat = judged[t].consistency();
  }
  int runner_up = best == &judged_pick ? std::numeric_limits<int>::min() : judged_pick.consistency();
  for (const Judged& twin : judged) {
    if (&twin != best) runner_up = std::max(runner_up, twin.consistency());
  }
  Detection chosen = best->pose.detection;
  chosen.seen_through = best->seenThroughShare();
  if (runner_up != std::numeric_limits<int>::min()) {
    chosen.twin_margin = std::min(1.0f, static_cast<float>(best->consistency() - runner_up) /
                                            static_cast<float>(std::max(1, best->agreement.visible)));
  }
  return chosen;
}

}  // namespace binpick::estimation
