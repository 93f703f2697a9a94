#include "binpick/estimation/detector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "binpick/core/error.hpp"
#include "binpick/core/stopwatch.hpp"
#include "binpick/core/thread_count.hpp"
#include "binpick/estimation/range_agreement.hpp"
#include "point_ops.hpp"

namespace binpick::estimation {
namespace {

bool repeatsAccepted(const std::vector<Detection>& accepted, const Eigen::Vector3f& centre, const PreparedModel& model,
                     float min_distance) {
  for (const Detection& d : accepted) {
    if ((d.T_camera_model * model.centre - centre).norm() < min_distance) return true;
  }
  return false;
}

// A refined pose and its fit.
struct Refined {
  Detection detection;
  PoseFit fit;
};

Refined refined(const PoseRefiner& refiner, const PreparedModel& model, const Eigen::Isometry3f& pose,
                int max_iterations) {
  const IcpResult icp = refiner.refine(model, pose, max_iterations);
  Refined r;
  r.detection.T_camera_model = icp.T_camera_model;
  r.detection.coverage = icp.coverage;
  r.detection.icp_rmse = icp.rmse;
  r.detection.icp_iterations = icp.iterations;
  r.fit = icp.fit;
  return r;
}

// A pose with the range's judgement of it (range_agreement.hpp).
struct Judged {
  Refined pose;
  RangeAgreement agreement;
  bool judged = false;
  int consistency() const { return judged ? agreement.consistency() : std::numeric_limits<int>::min(); }
  float seenThroughShare() const {
    return agreement.visible == 0 ? 0.0f
                                  : static_cast<float>(agreement.seen_through) / static_cast<float>(agreement.visible);
  }
};

// A turned twin, refined; or where it started when ICP made it agree less with the range (ICP can
// slide a part lying on one face along it, off its outline). Not judged when it agrees with the
// range less than `floor` before ICP: it could not win after.
Judged judgedTwin(const PoseRefiner& refiner, const PreparedModel& model, const LineOfSightMap& map,
                  const Eigen::Isometry3f& turned, float tolerance, int max_iterations, int floor) {
  Judged twin;
  const RangeAgreement start = rangeAgreement(model, turned, map, tolerance);
  if (start.consistency() < floor) return twin;
  twin.judged = true;
  twin.pose = refined(refiner, model, turned, max_iterations);
  twin.agreement = rangeAgreement(model, twin.pose.detection.T_camera_model, map, tolerance);
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

// A pick and its turned twins (near_symmetries.hpp) explain nearly the same scene points when the
// part shows a single face: each twin that agrees nearly as well with the measured range is
// refined too, and the pose whose fine surface the range explains most, less what the camera saw
// through (range_agreement.hpp), is kept. A twin must win by a margin, so that noise does not swap
// poses that are equally good; only a `turned` twin may win, a `slid` one weighs on the margin.
// The chosen pose's seen-through share is its range's.
Detection mostConsistent(const PoseRefiner& refiner, const PreparedModel& model, const LineOfSightMap& map,
                         const Refined& pick, const NearSymmetries& near_symmetries, float tolerance,
                         int max_iterations, int threads) {
  Judged judged_pick{pick, rangeAgreement(model, pick.detection.T_camera_model, map, tolerance), true};
  const std::size_t turned = near_symmetries.turned.size();
  const auto turn = [&](std::size_t t) -> const Eigen::Isometry3f& {
    return t < turned ? near_symmetries.turned[t] : near_symmetries.slid[t - turned];
  };
  std::vector<Judged> twins(turned + near_symmetries.slid.size());
  // The twins are independent: judged side by side (refine() is const and thread-safe), with a
  // third of the iterations: registered onto the model, each starts within millimetres of its fit.
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
  for (std::size_t t = 0; t < twins.size(); ++t) {
    twins[t] = judgedTwin(refiner, model, map, pick.detection.T_camera_model * turn(t), tolerance, max_iterations / 3,
                          judged_pick.consistency() * 4 / 5);
  }
  const Judged* best = &judged_pick;
  int to_beat = judged_pick.consistency() + std::max(3, judged_pick.agreement.visible / 50);
  for (std::size_t t = 0; t < turned; ++t) {
    if (twins[t].consistency() > to_beat) best = &twins[t], to_beat = twins[t].consistency();
  }
  int runner_up = best == &judged_pick ? std::numeric_limits<int>::min() : judged_pick.consistency();
  for (const Judged& twin : twins) {
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

// Sections III-C and III-D: verification, then Algorithm 1 picks poses one by one; each pick is
// refined by ICP before its scene points stop existing, so that a coarse candidate does not leave
// half of its object behind for a repeat detection.
void selectVerified(const PreparedModel& model, const PreparedScene& scene, const DetectorParams& p,
                    const std::vector<PoseCandidate>& candidates, DetectionResult& result, core::Stopwatch& clock,
                    const core::CancelFlag* cancel) {
  static const NearSymmetries kNoTwins;
  const NearSymmetries& near_symmetries = p.verification.compare_turned ? model.near_symmetries : kNoTwins;
  const SceneVoxelGrid grid(scene.points, p.verification.voxel_size_ratio * model.step);
  const std::vector<VerifiedCandidate> verified = verify(candidates, model, scene, grid, p.verification, cancel);
  result.timing_ms.verification = clock.lapMs();

  const float refined_tolerance = p.verification.refined_tolerance_ratio * model.step;
  const PoseRefiner refiner(scene, model.step, p.icp);
  // Scene-consistent verification: a candidate's free-space penalty is computed when Algorithm 1
  // first refreshes it (most candidates never are).
  const int threads = core::resolveThreadCount(p.threads);
  MultipleSelection selection(
      verified, scene.size(),
      [&](uint32_t c) { return freeSpacePenalty(model, scene, verified[c].T_camera_model, p.verification); }, threads);
  const float removal_radius = 1.5f * grid.voxelSize();
  const auto min_score = static_cast<uint32_t>(std::ceil(p.selection.min_score_fraction * model.size()));
  const float min_distance = p.selection.min_centre_distance_ratio * model.diameter;
  double icp_ms = 0.0;
  while (static_cast<int>(result.detections.size()) < p.selection.max_objects) {
    const auto pick = selection.next();
    if (!pick || pick->score < std::max(min_score, 1u)) break;
    // A candidate already sitting on an accepted part is a repeat whatever ICP makes of it (no two
    // parts have centres that close): skip it before paying for ICP. Repeats do not remove scene
    // points, so a cloud that yields many of them (e.g. many candidates on one flat face) would
    // otherwise spend most of its time refining them.
    const Eigen::Isometry3f& candidate = verified[pick->candidate].T_camera_model;
    if (repeatsAccepted(result.detections, candidate * model.centre, model, min_distance)) {
      continue;
    }
    core::throwIfCancelled(cancel, "during selection");
    const core::Stopwatch icp_clock;
    const Refined first = refined(refiner, model, candidate, p.icp.max_iterations);
    if (repeatsAccepted(result.detections, first.detection.T_camera_model * model.centre, model, min_distance)) {
      icp_ms += icp_clock.elapsedMs();
      continue;
    }
    // Scene-consistent verification again at the refined pose, tighter, and against the pick
    // turned over: ICP may have pulled a candidate onto the one face of a part turned over.
    Detection d = mostConsistent(refiner, model, scene.line_of_sight, first, near_symmetries, refined_tolerance,
                                 p.icp.max_iterations, threads);
    icp_ms += icp_clock.elapsedMs();
    if (d.seen_through > p.verification.max_refined_seen_through) {
      ++result.seen_through_rejected;
      continue;
    }
    if (d.coverage < p.selection.min_coverage) continue;  // refined onto nothing: no part there
    d.score = static_cast<float>(pick->score) / static_cast<float>(model.size());
    d.votes = verified[pick->candidate].votes;
    // Algorithm 1 lines 2-6, at the refined pose and for every scene point within the fit
    // tolerance: a voxel holds one scene point, so removing only those leaves most of a flat face
    // existing, and candidates sliding over that face would be picked (and refined) again and again.
    selection.removeExplained(refiner.scenePointsNear(model, d.T_camera_model, removal_radius));
    result.detections.push_back(d);
  }
  // What a robot acts on first should be what the range is sure of: a pose it cannot tell from the
  // part turned over, or one that explains little of what the camera should see, goes last.
  for (Detection& d : result.detections) {
    const bool told_apart = p.selection.sure_twin_margin == 0.0f || d.twin_margin >= p.selection.sure_twin_margin;
    d.sure = told_apart && d.coverage >= p.selection.sure_coverage;
  }
  std::stable_partition(result.detections.begin(), result.detections.end(), [](const Detection& d) { return d.sure; });
  result.refreshes = selection.refreshCount();
  result.timing_ms.icp = icp_ms;
  result.timing_ms.selection = clock.lapMs() - icp_ms;
}

// Section II-C: clusters of poses, best first, each refined; repeats of an accepted pose skipped.
void selectClustered(const PreparedModel& model, const PreparedScene& scene, const DetectorParams& p,
                     const std::vector<PoseCandidate>& candidates, DetectionResult& result, core::Stopwatch& clock,
                     const core::CancelFlag* cancel) {
  const std::vector<PoseCluster> clusters = clusterPoses(candidates, model.diameter, p.clustering);
  core::throwIfCancelled(cancel, "after clustering");
  result.timing_ms.selection = clock.lapMs();
  const PoseRefiner refiner(scene, model.step, p.icp);
  const float min_distance = p.selection.min_centre_distance_ratio * model.diameter;
  for (const PoseCluster& cluster : clusters) {
    if (static_cast<int>(result.detections.size()) >= p.selection.max_objects) break;
    core::throwIfCancelled(cancel, "during selection");
    Detection d = refined(refiner, model, cluster.T_camera_model, p.icp.max_iterations).detection;
    if (repeatsAccepted(result.detections, d.T_camera_model * model.centre, model, min_distance)) continue;
    d.votes = cluster.votes;
    d.score = static_cast<float>(cluster.votes) / static_cast<float>(clusters.front().votes);
    result.detections.push_back(d);
  }
  result.timing_ms.icp = clock.lapMs();
}

}  // namespace

std::string sceneWarning(const DetectionResult& result) {
  const std::size_t subsampled = result.scene_points + result.scene_points_without_normal;
  if (result.scene_points_without_normal * 2 <= subsampled) return {};
  return std::to_string(result.scene_points_without_normal) + " of " + std::to_string(subsampled) +
         " subsampled scene points had too few neighbours for a normal and were dropped (is the cloud sparse, "
         "or mostly isolated points?)";
}

Method methodFromName(const std::string& name) {
  if (name == "li_hashimoto") return Method::LiHashimoto;
  if (name == "drost") return Method::Drost;
  throw core::Error("detector params: method '" + name + "' is unknown (li_hashimoto or drost)");
}

std::string methodName(Method method) { return method == Method::Drost ? "drost" : "li_hashimoto"; }

DetectorParams DetectorParams::drost(float reference_fraction) {
  DetectorParams p;
  p.method = Method::Drost;
  p.voting.reference_fraction = reference_fraction;
  p.voting.referred_fraction = 1.0f;
  p.voting.poses_per_reference = 3;
  p.voting.min_relative_votes = 0.9f;
  p.boundary.enabled = false;  // Drost's surface pairs only
  return p;
}

void DetectorParams::validate() const {
  if (threads < 0) throw core::Error("detector params: threads must be >= 0");
  scene.validate();
  voting.validate();
  boundary.validate();
  verification.validate();
  selection.validate();
  icp.validate();
  clustering.validate();
}

Detector::Detector(PreparedModel model, DetectorParams params) : model_(std::move(model)), params_(params) {
  params_.validate();
  params_.scene.threads = params_.voting.threads = params_.verification.threads = params_.boundary.threads =
      params_.threads;
  if (model_.size() == 0) throw core::Error("detector: the model has no points");
  if (params_.boundary.enabled) {
    const bool prepared = model_.boundary && model_.boundary_crease_angle_deg == params_.boundary.crease_angle_deg;
    boundary_model_ = prepared ? model_.boundary
                               : std::make_shared<const BoundaryModel>(prepareBoundaryModel(model_, params_.boundary));
  }
}

DetectionResult Detector::detect(const io::PointCloud& scene_cloud) const {
  return detect(scene_cloud, params_.scene.crop);
}

DetectionResult Detector::detect(const io::PointCloud& scene_cloud, const std::optional<CropBox>& crop,
                                 const core::CancelFlag* cancel) const {
  core::throwIfCancelled(cancel, "before detection");
  const core::Stopwatch total;
  core::Stopwatch clock;
  DetectionResult result;
  SceneParams scene_params = params_.scene;
  scene_params.crop = crop;
  const PreparedScene scene = prepareScene(scene_cloud, model_, scene_params);
  BoundaryPoints scene_boundary;
  if (boundary_model_) scene_boundary = sceneBoundaryPoints(scene_cloud, crop, model_, params_.boundary);
  result.scene_points = scene.size();
  result.scene_boundary_points = scene_boundary.size();
  result.scene_points_without_normal = scene.without_normal;
  result.timing_ms.prepare_scene = clock.lapMs();
  core::throwIfCancelled(cancel, "after scene preparation");

  std::optional<BoundaryVotes> boundary_votes;
  if (boundary_model_) boundary_votes.emplace(BoundaryVotes{*boundary_model_, scene_boundary});
  const std::vector<PoseCandidate> candidates =
      vote(model_, scene, params_.voting, cancel, boundary_votes ? &*boundary_votes : nullptr);
  result.candidates = candidates.size();
  result.timing_ms.voting = clock.lapMs();
  if (!candidates.empty()) {
    if (params_.method == Method::LiHashimoto) {
      selectVerified(model_, scene, params_, candidates, result, clock, cancel);
    } else {
      selectClustered(model_, scene, params_, candidates, result, clock, cancel);
    }
  }
  result.timing_ms.total = total.elapsedMs();
  return result;
}

}  // namespace binpick::estimation
