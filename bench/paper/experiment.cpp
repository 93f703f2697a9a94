#include "experiment.hpp"

#include <algorithm>
#include <cstdio>

#include "bench_support.hpp"
#include "binpick/core/stopwatch.hpp"
#include "binpick_method.hpp"

namespace binpick::bench {
namespace {

double ratio(double a, double b) { return b > 0.0 ? a / b : 0.0; }

// For a wrong detection: the nearest part, whether another detection found it, and the offset
// of the detection from it in the part's frame (mm) and the turn between them (no symmetry folded).
std::string nearestPart(const estimation::Detection& d, const std::vector<simulation::ObjectTruth>& truth,
                        const simulation::Part& part, const evaluation::Score& score) {
  const Nearest nearest = nearestObject(d.T_camera_model, truth, part.symmetry);
  if (nearest.object < 0) return "";
  const simulation::ObjectTruth& o = truth[static_cast<std::size_t>(nearest.object)];
  const Eigen::Isometry3d offset = o.T_camera_object.inverse() * d.T_camera_model.cast<double>();
  const Eigen::Vector3d mm = offset.translation() * 1000.0;
  const auto found_by = std::find(score.matched_object.begin(), score.matched_object.end(), nearest.object);
  const std::string found = found_by == score.matched_object.end()
                                ? "not found"
                                : "found by " + std::to_string(found_by - score.matched_object.begin());
  const Eigen::AngleAxisd turn(offset.linear());
  char text[200];
  std::snprintf(text, sizeof text,
                "; nearest object %d (%.0f%% visible, %s): offset (%.1f, %.1f, %.1f) mm, %.0f deg about (%.2f, %.2f, "
                "%.2f)",
                nearest.object, 100.0 * o.visible_fraction, found.c_str(), mm.x(), mm.y(), mm.z(),
                turn.angle() * 180.0 / M_PI, turn.axis().x(), turn.axis().y(), turn.axis().z());
  return text;
}

std::vector<std::string> explained(const std::vector<estimation::Detection>& detections,
                                   const std::vector<simulation::ObjectTruth>& truth, const simulation::Part& part,
                                   const evaluation::Score& score) {
  std::vector<std::string> lines;
  for (std::size_t k = 0; k < detections.size(); ++k) {
    const estimation::Detection& d = detections[k];
    const bool right = score.matched_object[k] >= 0;
    char line[160];
    std::snprintf(line, sizeof line, "detection %2zu %s: score %.2f coverage %.2f seen through %.2f twin margin %.3f%s",
                  k, right ? "right" : "WRONG", d.score, d.coverage, d.seen_through, d.twin_margin,
                  d.sure ? " sure" : "");
    lines.emplace_back(std::string(line) + (right ? "" : nearestPart(d, truth, part, score)));
  }
  return lines;
}

void addStages(estimation::StageTimings& sum, const estimation::StageTimings& t) {
  sum.prepare_scene += t.prepare_scene;
  sum.voting += t.voting;
  sum.verification += t.verification;
  sum.selection += t.selection;
  sum.icp += t.icp;
  sum.total += t.total;
}

}  // namespace

evaluation::Score scorePoses(const std::vector<Eigen::Isometry3f>& poses,
                             const std::vector<simulation::ObjectTruth>& truth, const simulation::Part& part,
                             double diameter) {
  std::vector<estimation::Detection> detections(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) detections[i].T_camera_model = poses[i];
  return evaluation::scoreDetections(detections, truth, part.symmetry, {diameter / 10.0, 10.0});
}

std::string describeScore(const evaluation::Score& s, std::size_t poses) {
  std::string text = "found " + std::to_string(s.found) + " of " + std::to_string(s.findable) + " findable, " +
                     std::to_string(poses) + " poses, matched objects:";
  for (int m : s.matched_object) text += " " + std::to_string(m);
  return text;
}

void Tally::add(const SceneOutcome& o) {
  ++scenes;
  objects += o.objects;
  findable += o.findable;
  found += o.found;
  detections += o.detections;
  correct += o.correct;
  wrong_in_first_10 += o.wrong_in_first_10;
  if (o.wrong_in_first_10 > 0) ++scenes_wrong_in_first_10;
  ms += o.ms;
  if (o.stages) addStages(stages, *o.stages);
}

double Tally::recognitionRate() const { return ratio(correct, objects); }
double Tally::precision() const { return ratio(correct, detections); }
double Tally::recall() const { return ratio(found, findable); }
double Tally::msPerObject() const { return ratio(ms, objects); }

SceneOutcome runMethod(const PoseMethod& method, const BenchScene& scene, CloudInput input,
                       const simulation::Part& part, double diameter) {
  const MethodInput method_input{&scene.cloud(input), scene.crop};
  SceneOutcome o;
  o.part = part.name;
  o.method = method.name();
  o.input = input;
  o.seed = scene.params.seed;
  o.objects = static_cast<int>(scene.truth.objects.size());
  o.input_points = scene.pointsInBin(input);

  std::vector<Eigen::Isometry3f> poses;
  std::vector<estimation::Detection> details;
  const core::Stopwatch stopwatch;
  if (const auto* own = dynamic_cast<const BinpickMethod*>(&method)) {
    const estimation::DetectionResult result = own->detectWithDetails(method_input);
    o.stages = result.timing_ms;
    details = result.detections;
    for (const estimation::Detection& d : result.detections) poses.push_back(d.T_camera_model);
  } else {
    poses = method.detect(method_input);
  }
  o.ms = stopwatch.elapsedMs();

  const evaluation::Score score = scorePoses(poses, scene.truth.objects, part, diameter);
  o.explanation = explained(details, scene.truth.objects, part, score);
  o.findable = score.findable;
  o.found = score.found;
  o.detections = static_cast<int>(poses.size());
  o.correct = score.correct;
  o.wrong_in_first_10 = score.wrong_in_first_10;
  return o;
}

void writeOutcomeHeader(std::ostream& out) {
  out << "part,method,input,seed,objects,findable,found,detections,correct,ms,input_points,wrong_in_first_10\n";
}

void writeOutcome(std::ostream& out, const SceneOutcome& o) {
  out << o.part << ',' << o.method << ',' << inputName(o.input) << ',' << o.seed << ',' << o.objects << ','
      << o.findable << ',' << o.found << ',' << o.detections << ',' << o.correct << ',' << o.ms << ',' << o.input_points
      << ',' << o.wrong_in_first_10 << '\n';
}

}  // namespace binpick::bench
