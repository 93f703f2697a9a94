// Estimation benchmark on virtual-cell piles: ms per object (whole pipeline and per stage),
// recognition rate of the objects at least half visible, and wrong detections among the first 10,
// for the paper's method and its Drost baselines (Table I).
//
//   bench_estimation [--parts l_bracket,clamp] [--meshes FILE[:SCALE],...] [--scenes 5] [--objects 20]
//                    [--seed 1] [--method li_hashimoto|ppf1|ppf5] [--threads 0]
//                    [--max-pairs-per-feature 2000] [--reduce-by-symmetry 1] [--settings detection.yaml]
//                    [--explain 1] [--binpick FILE]
// --meshes: parts of one's own (an STL in millimetres: FILE:0.001), their symmetry found from the
// mesh. The whole process: with the proposed method's defaults, each scene is also detected by
// `binpick detect` (FILE, by default the one built beside this benchmark; "none": not) from a
// model cache prepared beforehand, and its wall time (start, cache, scene file, detection, result
// file) is reported per object next to the detector's own, with the cache's load time.
// --settings: the proposed method's detector settings from a detection.yaml (e.g. a deviation
// switched off); --explain 1: one line per detection (error against the nearest part; for a wrong
// one, how it and the truth agree with the measured range) and per missed half-visible part (its
// nearest detection, and how it lies).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <unistd.h>

#include "bench_support.hpp"
#include "binpick/core/error.hpp"
#include "binpick/core/pose_yaml.hpp"
#include "binpick/core/stopwatch.hpp"
#include "binpick/estimation/config.hpp"
#include "binpick/estimation/detector.hpp"
#include "binpick/estimation/model_cache.hpp"
#include "binpick/evaluation/evaluation.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/pile.hpp"
#include "icp.hpp"
#include "range_agreement.hpp"

namespace {

using namespace binpick;

namespace fs = std::filesystem;

struct Options {
  std::vector<std::string> parts{"l_bracket", "clamp"};
  std::vector<std::string> meshes;
  int scenes = 5;
  int objects = 20;
  uint64_t seed = 1;
  std::string method = "li_hashimoto";
  int threads = 0;
  uint32_t max_pairs_per_feature = estimation::ModelParams{}.max_pairs_per_feature;
  std::string settings;  // a detection.yaml for li_hashimoto; empty: the defaults
  bool reduce_by_symmetry = true;
  bool explain = false;
  std::string binpick;  // the CLI timed as a whole process; empty: none
};

using bench::Nearest;
using bench::nearestObject;
using bench::splitCommas;

Options parse(int argc, char** argv) {
  Options o;
  const fs::path beside = fs::path(argv[0]).parent_path() / ".." / "src" / "cli" / "binpick";
  if (fs::exists(beside)) o.binpick = beside.string();
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (i + 1 >= argc) throw core::Error("bench_estimation: " + flag + " needs a value");
    const std::string value = argv[++i];
    if (flag == "--parts")
      o.parts = splitCommas(value);
    else if (flag == "--meshes")
      o.meshes = splitCommas(value);
    else if (flag == "--reduce-by-symmetry")
      o.reduce_by_symmetry = value != "0";
    else if (flag == "--binpick")
      o.binpick = value == "none" ? "" : value;
    else if (flag == "--scenes")
      o.scenes = std::stoi(value);
    else if (flag == "--objects")
      o.objects = std::stoi(value);
    else if (flag == "--seed")
      o.seed = std::stoull(value);
    else if (flag == "--method")
      o.method = value;
    else if (flag == "--threads")
      o.threads = std::stoi(value);
    else if (flag == "--max-pairs-per-feature")
      o.max_pairs_per_feature = static_cast<uint32_t>(std::stoul(value));
    else if (flag == "--settings")
      o.settings = value;
    else if (flag == "--explain")
      o.explain = value != "0";
    else
      throw core::Error("bench_estimation: unknown option " + flag);
  }
  if (o.scenes < 1 || o.objects < 1) throw core::Error("bench_estimation: --scenes and --objects must be >= 1");
  return o;
}

estimation::DetectorParams detectorParams(const Options& o) {
  estimation::DetectorParams p;
  if (o.method == "ppf1")
    p = estimation::DetectorParams::drost(1.0f);
  else if (o.method == "ppf5")
    p = estimation::DetectorParams::drost(0.2f);
  else if (o.method != "li_hashimoto")
    throw core::Error("bench_estimation: --method must be li_hashimoto, ppf1 or ppf5");
  else if (!o.settings.empty())
    p = estimation::loadEstimationConfig(o.settings).detector;
  p.selection.max_objects = o.objects;
  p.threads = o.threads;
  return p;
}

struct Totals {
  estimation::StageTimings ms;
  int findable = 0, found = 0, detections = 0, correct = 0, wrong_first_10 = 0, scene_points = 0;
  std::size_t input_points = 0;
  void add(const estimation::DetectionResult& r, const evaluation::Score& s, std::size_t valid_points) {
    ms.prepare_scene += r.timing_ms.prepare_scene;
    ms.voting += r.timing_ms.voting;
    ms.verification += r.timing_ms.verification;
    ms.selection += r.timing_ms.selection;
    ms.icp += r.timing_ms.icp;
    ms.total += r.timing_ms.total;
    findable += s.findable;
    found += s.found;
    detections += static_cast<int>(r.detections.size());
    correct += s.correct;
    wrong_first_10 += s.wrong_in_first_10;
    scene_points += static_cast<int>(r.scene_points);
    input_points += valid_points;
  }
};

std::size_t validPoints(const io::PointCloud& cloud) {
  std::size_t n = 0;
  for (const auto& p : cloud.points) n += p.allFinite() ? 1 : 0;
  return n;
}

// The detector's own measure of a pose (range_agreement.hpp), for a wrong detection and for the
// part's true pose, before and after ICP: tells a search failure (the truth agrees better) from a
// scoring one (it does not), and shows ICP drifting off the truth.
struct Judge {
  const estimation::PreparedModel& model;
  const estimation::PreparedScene& scene;
  const estimation::PoseRefiner& refiner;
  float tolerance;
};
void explainWrong(const Eigen::Isometry3f& detected, const Eigen::Isometry3f& truth, const Judge& judge) {
  const auto agreement = [&](const Eigen::Isometry3f& pose) {
    const estimation::RangeAgreement a =
        estimation::rangeAgreement(judge.model, pose, judge.scene.line_of_sight, judge.tolerance);
    return std::to_string(a.explained) + " - " + std::to_string(a.seen_through) + " of " + std::to_string(a.visible);
  };
  const Eigen::Isometry3f refined = judge.refiner.refine(judge.model, truth).T_camera_model;
  const Eigen::Isometry3f drift = truth.inverse() * refined;
  std::printf("      explained - seen through: detected %s; truth %s; truth after ICP %s (moved %.1f mm %.1f deg)\n",
              agreement(detected).c_str(), agreement(truth).c_str(), agreement(refined).c_str(),
              drift.translation().norm() * 1000.0, Eigen::AngleAxisf(drift.linear()).angle() * 180.0 / M_PI);
}

// What each detection is and what each missed half-visible part lacked: the data behind a
// recognition rate.
void explain(const estimation::DetectionResult& result, const evaluation::Score& score,
             const simulation::PileScene& scene, const simulation::Part& part, const Judge& judge) {
  std::printf("  %zu candidates, %zu refined picks refused (seen through), %zu scene boundary points\n",
              result.candidates, result.seen_through_rejected, result.scene_boundary_points);
  for (std::size_t k = 0; k < result.detections.size(); ++k) {
    const estimation::Detection& d = result.detections[k];
    const Nearest n = nearestObject(d.T_camera_model, scene.objects, part.symmetry);
    std::printf(
        "    detection %2zu %-5s part %2d: %6.1f mm %5.1f deg; score %.2f coverage %.2f seen through %.2f"
        " twin margin %.3f\n",
        k, score.matched_object[k] >= 0 ? "right" : "WRONG", n.object, n.error.translation * 1000.0,
        n.error.rotation_deg, d.score, d.coverage, d.seen_through, d.twin_margin);
    if (score.matched_object[k] < 0 && n.object >= 0) {
      explainWrong(d.T_camera_model, scene.objects[static_cast<std::size_t>(n.object)].T_camera_object.cast<float>(),
                   judge);
    }
  }
  for (std::size_t j = 0; j < scene.objects.size(); ++j) {
    const simulation::ObjectTruth& object = scene.objects[j];
    if (object.visible_fraction < 0.5) continue;
    if (std::find(score.matched_object.begin(), score.matched_object.end(), static_cast<int>(j)) !=
        score.matched_object.end()) {
      continue;
    }
    simulation::PoseError nearest{1e9, 0.0};
    for (const estimation::Detection& d : result.detections) {
      const auto e = simulation::poseError(d.T_camera_model.cast<double>(), object.T_camera_object, part.symmetry);
      if (e.translation < nearest.translation) nearest = e;
    }
    // The angle between the model's z axis and the line of sight: near 0, the part shows its z face.
    const Eigen::Vector3d towards_camera = -object.T_camera_object.translation().normalized();
    const double z_angle =
        std::acos(std::min(1.0, std::abs(object.T_camera_object.linear().col(2).dot(towards_camera)))) * 180.0 / M_PI;
    std::printf(
        "    missed part %2zu (%.0f%% visible, z axis %2.0f deg from the view): nearest detection %.1f mm %.1f deg\n",
        j, 100.0 * object.visible_fraction, z_angle, nearest.translation * 1000.0, nearest.rotation_deg);
  }
}

// The whole process as a user runs it: `binpick detect` on a scene's cloud file, from a model
// cache prepared beforehand, in a directory of its own that is removed afterwards.
class WholeProcess {
 public:
  WholeProcess(const Options& o, const simulation::Part& part, const estimation::PreparedModel& model)
      : options_(o),
        dir_(fs::temp_directory_path() / ("bench_estimation_" + std::to_string(::getpid()) + "_" + part.name)) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    io::writeMesh(path("model.ply"), part.mesh);
    estimation::saveModelCache(model, estimation::fingerprintFile(path("model.ply")), path("model.cache"));
  }
  ~WholeProcess() {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }

  double cacheMegabytes() const { return static_cast<double>(fs::file_size(path("model.cache"))) / 1e6; }

  // The fastest of three loads of the model cache, ms.
  double cacheLoadMs() const {
    double fastest = 1e30;
    for (int k = 0; k < 3; ++k) {
      const core::Stopwatch clock;
      const estimation::CachedModel cached = estimation::loadModelCache(path("model.cache"));
      fastest = std::min(fastest, clock.elapsedMs());
    }
    return fastest;
  }

  // Wall ms of `binpick detect` on the scene; throws when it fails.
  double detectMs(const simulation::PileScene& scene, const estimation::CropBox& crop) const {
    io::writePointCloud(path("cloud.ply"), scene.cloud);
    writeConfig(crop);
    const std::string command = "'" + options_.binpick + "' detect --model '" + path("model.ply") +
                                "' --model-cache '" + path("model.cache") + "' --scene '" + path("cloud.ply") +
                                "' --config '" + path("config.yaml") + "' --out '" + path("result.json") +
                                "' 2>/dev/null";
    const auto start = std::chrono::steady_clock::now();
    const int status = std::system(command.c_str());
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (status != 0) throw core::Error("bench_estimation: " + command + " failed");
    return ms;
  }

 private:
  std::string path(const char* name) const { return (dir_ / name).string(); }

  void writeConfig(const estimation::CropBox& crop) const {
    std::ofstream yaml(path("config.yaml"));
    yaml.precision(9);
    yaml << "model:\n  max_pairs_per_feature: " << options_.max_pairs_per_feature
         << "\n  reduce_by_symmetry: " << (options_.reduce_by_symmetry ? "true" : "false")
         << "\ndetection:\n  threads: " << options_.threads << "\n  selection:\n    max_objects: " << options_.objects
         << "\n  scene:\n    crop:\n"
         << "      pose:\n"
         << core::poseYaml(crop.T_camera_box.cast<double>(), "        ") << "      half_extents: ["
         << crop.half_extents.x() << ", " << crop.half_extents.y() << ", " << crop.half_extents.z() << "]\n";
  }

  const Options& options_;
  fs::path dir_;
};

void benchPart(const simulation::Part& part, const Options& o) {
  estimation::ModelParams model_params;
  model_params.max_pairs_per_feature = o.max_pairs_per_feature;
  model_params.reduce_by_symmetry = o.reduce_by_symmetry;
  const core::Stopwatch preparation;
  const estimation::PreparedModel model = estimation::prepareModel(io::ModelGeometry{part.mesh, {}}, model_params);
  const double preparation_ms = preparation.elapsedMs();
  estimation::DetectorParams params = detectorParams(o);
  const bool time_process = !o.binpick.empty() && o.settings.empty() && o.method == "li_hashimoto";
  std::optional<WholeProcess> process;
  if (time_process) process.emplace(o, part, model);
  double process_ms = 0.0;
  Totals totals;
  for (int s = 0; s < o.scenes; ++s) {
    simulation::PileParams pile;
    pile.objects = o.objects;
    pile.seed = o.seed + static_cast<uint64_t>(s);
    const simulation::PileScene scene = simulation::generatePile(part.mesh, pile);
    params.scene.crop = evaluation::binInterior(scene, pile);
    const estimation::Detector detector(model, params);
    const estimation::DetectionResult result = detector.detect(scene.cloud);
    if (process) process_ms += process->detectMs(scene, *params.scene.crop);
    const evaluation::Score score =
        evaluation::scoreDetections(result.detections, scene.objects, part.symmetry, {model.diameter / 10.0, 10.0});
    totals.add(result, score, validPoints(scene.cloud));
    if (o.explain) {
      const estimation::PreparedScene prepared = estimation::prepareScene(scene.cloud, model, params.scene);
      const float tolerance = params.verification.refined_tolerance_ratio * model.step;
      const estimation::PoseRefiner refiner(prepared, model.step, params.icp);
      explain(result, score, scene, part, {model, prepared, refiner, tolerance});
    }
  }
  const double objects = static_cast<double>(o.scenes) * o.objects;
  const auto per_object = [&](double ms) { return ms / objects; };
  std::printf(
      "%-10s %-12s model %zu pts (%zu references, symmetry %s, %zu + %zu turned and slid twins), %zu pairs, prepared "
      "in %.0f ms | scenes %d x %d objects, %.0fk pts/scene, %d subsampled\n",
      part.name.c_str(), o.method.c_str(), model.size(), model.referenceCount(), model.symmetry.describe().c_str(),
      model.near_symmetries.turned.size(), model.near_symmetries.slid.size(), model.table.pairCount(), preparation_ms,
      o.scenes, o.objects, totals.input_points / 1000.0 / o.scenes, totals.scene_points / o.scenes);
  std::printf(
      "  ms/object %.1f (scene %.1f, voting %.1f, verification %.1f, selection %.2f, icp %.1f); ms/scene %.0f\n",
      per_object(totals.ms.total), per_object(totals.ms.prepare_scene), per_object(totals.ms.voting),
      per_object(totals.ms.verification), per_object(totals.ms.selection), per_object(totals.ms.icp),
      totals.ms.total / o.scenes);
  if (process) {
    std::printf(
        "  whole process (binpick detect) ms/object %.1f, %.2fx the detector's; model cache %.1f MB, loads in %.1f "
        "ms\n",
        per_object(process_ms), process_ms / std::max(1e-9, totals.ms.total), process->cacheMegabytes(),
        process->cacheLoadMs());
  }
  std::printf(
      "  recognition %.1f%% (%d/%d objects >= 50%% visible), detections %d, correct %d, wrong in first 10: %d\n",
      totals.findable ? 100.0 * totals.found / totals.findable : 0.0, totals.found, totals.findable, totals.detections,
      totals.correct, totals.wrong_first_10);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options options = parse(argc, argv);
    for (const std::string& part : options.parts) benchPart(simulation::makePart(part), options);
    for (const std::string& spec : options.meshes) benchPart(bench::meshPart(spec), options);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
}
