#include "binpick/estimation/detector.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "binpick/core/error.hpp"
#include "binpick/core/stopwatch.hpp"
#include "binpick/core/thread_count.hpp"
#include "boundary.hpp"
#include "clustering.hpp"
#include "icp.hpp"
#include "scene.hpp"
#include "selection.hpp"
#include "twin_choice.hpp"
#include "verification.hpp"
#include "voting.hpp"
#include "voxel_grid.hpp"

namespace binpick::estimation {

struct Detector::Prepared {
  PreparedModel model;
  DetectorParams params;
  std::shared_ptr<const BoundaryModel> boundary_model;  // boundary.enabled: the model's, or one of its own
  int threads = 1;                                      // params.threads resolved
};

namespace {

// What every selection stage works on, for one detect() call.
struct SceneWork {
  const PreparedModel& model;
  const PreparedScene& scene;
  const DetectorParams& params;
  int threads;
  const core::CancelFlag* cancel;
};

// What a selection stage gives back: the detections in order and what it cost.
struct Selected {
  std::vector<Detection> detections;
  std::size_t refreshes = 0;              // eq. 4 evaluations during Algorithm 1
  std::size_t seen_through_rejected = 0;  // refined picks refused: the camera saw through them
  double verification_ms = 0, selection_ms = 0, icp_ms = 0;
};

bool repeatsAccepted(const std::vector<Detection>& accepted, const Eigen::Vector3f& centre, const PreparedModel& model,
                     float min_distance) {
  for (const Detection& d : accepted) {
    if ((d.T_camera_model * model.centre - centre).norm() < min_distance) return true;
  }
  return false;
}

// Algorithm 1 with ICP after each pick (section III-D): each pick is refined before its scene
// points stop existing, so that a coarse candidate does not leave half of its object behind for a
// repeat detection. Returns the accepted detections in selection order.
Selected refinedSelection(const SceneWork& work, const std::vector<VerifiedCandidate>& verified, float voxel_size) {
  const PreparedModel& model = work.model;
  const DetectorParams& p = work.params;
  static const NearSymmetries kNoTwins;
  const TwinJudging judging{work.scene.line_of_sight, p.verification.refined_tolerance_ratio * model.step,
                            p.icp.max_iterations, work.threads};
  const NearSymmetries& twins = p.verification.compare_turned ? model.near_symmetries : kNoTwins;
  const PoseRefiner refiner(work.scene, model.step, p.icp, work.threads);
  // Scene-consistent verification: a candidate's free-space penalty is computed when Algorithm 1
  // first refreshes it (most candidates never are).
  const auto min_score = static_cast<uint32_t>(std::ceil(p.selection.min_score_fraction * model.size()));
  MultipleSelection selection(
      verified, work.scene.size(),
      [&](uint32_t c) { return freeSpacePenalty(model, work.scene, verified[c].T_camera_model, p.verification); },
      work.threads, std::max(min_score, 1u));
  const float removal_radius = 1.5f * voxel_size;
  const float min_distance = p.selection.min_centre_distance_ratio * model.diameter;
  Selected selected;
  while (static_cast<int>(selected.detections.size()) < p.selection.max_objects) {
    const auto pick = selection.next();
    if (!pick) break;
    // A candidate already sitting on an accepted part is a repeat whatever ICP makes of it (no two
    // parts have centres that close): skip it before paying for ICP. Repeats do not remove scene
    // points, so a cloud that yields many of them (e.g. many candidates on one flat face) would
    // otherwise spend most of its time refining them.
    const Eigen::Isometry3f& candidate = verified[pick->candidate].T_camera_model;
    if (repeatsAccepted(selected.detections, candidate * model.centre, model, min_distance)) continue;
    core::throwIfCancelled(work.cancel, "during selection");
    const core::Stopwatch icp_clock;
    const RefinedPose first = refinedPose(refiner, model, candidate, p.icp.max_iterations);
    if (repeatsAccepted(selected.detections, first.detection.T_camera_model * model.centre, model, min_distance)) {
      selected.icp_ms += icp_clock.elapsedMs();
      continue;
    }
    // Scene-consistent verification again at the refined pose, tighter, and against the pick
    // turned over: ICP may have pulled a candidate onto the one face of a part turned over.
    Detection d = mostConsistent(refiner, model, first, twins, judging);
    selected.icp_ms += icp_clock.elapsedMs();
    if (d.seen_through > p.verification.max_refined_seen_through) {
      ++selected.seen_through_rejected;
      continue;
    }
    if (d.coverage < p.selection.min_coverage) continue;  // refined onto nothing: no part there
    d.score = static_cast<float>(pick->score) / static_cast<float>(model.size());
    d.votes = verified[pick->candidate].votes;
    // Algorithm 1 lines 2-6, at the refined pose and for every scene point within the fit
    // tolerance: a voxel holds one scene point, so removing only those leaves most of a flat face
    // existing, and candidates sliding over that face would be picked (and refined) again and again.
    selection.removeExplained(refiner.scenePointsNear(model, d.T_camera_model, removal_radius));
    selected.detections.push_back(d);
  }
  selected.refreshes = selection.refreshCount();
  return selected;
}

// What a robot acts on first should be what the range is sure of: a pose it cannot tell from the
// part turned over, or one that explains little of what the camera should see, goes last.
void orderSureFirst(std::vector<Detection>& detections, const SelectionParams& p) {
  for (Detection& d : detections) {
    const bool told_apart = p.sure_twin_margin == 0.0f || d.twin_margin >= p.sure_twin_margin;
    d.sure = told_apart && d.coverage >= p.sure_coverage;
  }
  std::stable_partition(detections.begin(), detections.end(), [](const Detection& d) { return d.sure; });
}

// Sections III-C and III-D: voxel verification of every candidate, then the refined selection,
// sure detections first.
Selected selectVerified(const SceneWork& work, const std::vector<PoseCandidate>& candidates) {
  core::Stopwatch clock;
  const SceneVoxelGrid grid(work.scene.points, work.params.verification.voxel_size_ratio * work.model.step);
  const std::vector<VerifiedCandidate> verified =
      verify(candidates, work.model, work.scene, grid, work.params.verification, work.cancel, work.threads);
  const double verification_ms = clock.lapMs();
  Selected selected = refinedSelection(work, verified, grid.voxelSize());
  orderSureFirst(selected.detections, work.params.selection);
  selected.verification_ms = verification_ms;
  selected.selection_ms = clock.lapMs() - selected.icp_ms;
  return selected;
}

// Section II-C: clusters of poses, best first, each refined; repeats of an accepted pose skipped.
Selected selectClustered(const SceneWork& work, const std::vector<PoseCandidate>& candidates) {
  const PreparedModel& model = work.model;
  const DetectorParams& p = work.params;
  core::Stopwatch clock;
  const std::vector<PoseCluster> clusters = clusterPoses(candidates, model.diameter, p.clustering);
  core::throwIfCancelled(work.cancel, "after clustering");
  Selected selected;
  selected.selection_ms = clock.lapMs();
  const PoseRefiner refiner(work.scene, model.step, p.icp, work.threads);
  const float min_distance = p.selection.min_centre_distance_ratio * model.diameter;
  for (const PoseCluster& cluster : clusters) {
    if (static_cast<int>(selected.detections.size()) >= p.selection.max_objects) break;
    core::throwIfCancelled(work.cancel, "during selection");
    Detection d = refinedPose(refiner, model, cluster.T_camera_model, p.icp.max_iterations).detection;
    if (repeatsAccepted(selected.detections, d.T_camera_model * model.centre, model, min_distance)) continue;
    d.votes = cluster.votes;
    d.score = static_cast<float>(cluster.votes) / static_cast<float>(clusters.front().votes);
    selected.detections.push_back(d);
  }
  selected.icp_ms = clock.lapMs();
  return selected;
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
  core::requireField(threads >= 0, "detection", "threads", ">= 0 (0: all hardware threads)", threads);
  scene.validate();
  voting.validate();
  boundary.validate();
  verification.validate();
  selection.validate();
  icp.validate();
  clustering.validate();
}

Detector::Detector(PreparedModel model, DetectorParams params) {
  params.validate();
  if (model.size() == 0) throw core::Error("detector: the model has no points");
  auto prepared = std::make_shared<Prepared>();
  if (params.boundary.enabled) {
    const bool cached = model.boundary && model.boundary_crease_angle_deg == params.boundary.crease_angle_deg;
    prepared->boundary_model =
        cached ? model.boundary : std::make_shared<const BoundaryModel>(prepareBoundaryModel(model, params.boundary));
  }
  prepared->model = std::move(model);
  prepared->params = params;
  prepared->threads = core::resolveThreadCount(params.threads);
  prepared_ = std::move(prepared);
}

const PreparedModel& Detector::model() const { return prepared_->model; }
const DetectorParams& Detector::params() const { return prepared_->params; }

DetectionResult Detector::detect(const io::PointCloud& scene_cloud) const {
  return detect(scene_cloud, prepared_->params.scene.crop);
}

DetectionResult Detector::detect(const io::PointCloud& scene_cloud, const std::optional<CropBox>& crop,
                                 const core::CancelFlag* cancel) const {
  core::throwIfCancelled(cancel, "before detection");
  const PreparedModel& model = prepared_->model;
  const DetectorParams& params = prepared_->params;
  const int threads = prepared_->threads;
  const core::Stopwatch total;
  core::Stopwatch clock;
  DetectionResult result;
  SceneParams scene_params = params.scene;
  scene_params.crop = crop;
  const PreparedScene scene = prepareScene(scene_cloud, model, scene_params, threads);
  BoundaryPoints scene_boundary;
  if (prepared_->boundary_model) {
    scene_boundary = sceneBoundaryPoints(scene_cloud, crop, model, params.boundary, threads);
  }
  result.scene_points = scene.size();
  result.scene_boundary_points = scene_boundary.size();
  result.scene_points_without_normal = scene.without_normal;
  result.timing_ms.prepare_scene = clock.lapMs();
  core::throwIfCancelled(cancel, "after scene preparation");

  std::optional<BoundaryVotes> boundary_votes;
  if (prepared_->boundary_model) boundary_votes.emplace(BoundaryVotes{*prepared_->boundary_model, scene_boundary});
  const std::vector<PoseCandidate> candidates =
      vote(model, scene, params.voting, cancel, boundary_votes ? &*boundary_votes : nullptr, threads);
  result.candidates = candidates.size();
  result.timing_ms.voting = clock.lapMs();
  if (!candidates.empty()) {
    const SceneWork work{model, scene, params, threads, cancel};
    Selected selected =
        params.method == Method::LiHashimoto ? selectVerified(work, candidates) : selectClustered(work, candidates);
    result.detections = std::move(selected.detections);
    result.refreshes = selected.refreshes;
    result.seen_through_rejected = selected.seen_through_rejected;
    result.timing_ms.verification = selected.verification_ms;
    result.timing_ms.selection = selected.selection_ms;
    result.timing_ms.icp = selected.icp_ms;
  }
  result.timing_ms.total = total.elapsedMs();
  return result;
}

}  // namespace binpick::estimation
