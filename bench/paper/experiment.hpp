#pragma once
// The paper's synthetic experiment (section IV-A): every method on the same scenes, scored with
// the paper's criterion, timed over the whole process.
#include <map>
#include <ostream>
#include <string>
#include <tuple>
#include <vector>

#include "bench_scenes.hpp"
#include "binpick/estimation/detector.hpp"
#include "binpick/evaluation/evaluation.hpp"
#include "pose_method.hpp"

namespace binpick::bench {

// One method on one scene and one input.
struct SceneOutcome {
  std::string part, method;
  CloudInput input = CloudInput::Exact;
  uint64_t seed = 0;
  int objects = 0;   // objects in the bin
  int findable = 0;  // of those, at least half visible
  int found = 0;     // findable objects with a correct detection
  int detections = 0;
  int correct = 0;               // detections within diam/10 and 10 degrees of an object not claimed before
  int wrong_in_first_10 = 0;     // what a robot acts on first
  double ms = 0.0;               // detect(): the whole process
  std::size_t input_points = 0;  // finite points inside the bin
  // binpick's methods only: the detector's own stage timings.
  std::optional<estimation::StageTimings> stages;
  std::vector<std::string> explanation;  // binpick's methods: one line per detection
};

// Sums of outcomes, and the paper's figures from them.
struct Tally {
  int scenes = 0, objects = 0, findable = 0, found = 0, detections = 0, correct = 0;
  int wrong_in_first_10 = 0, scenes_wrong_in_first_10 = 0;
  double ms = 0.0;
  estimation::StageTimings stages;  // summed over the outcomes that had them
  void add(const SceneOutcome& outcome);
  double recognitionRate() const;  // correct / objects (Table II)
  double precision() const;        // correct / detections
  double recall() const;           // found / findable
  double msPerObject() const;      // Table III
};

// The paper's criterion on poses in order: correct within diam/10 and 10 degrees of an object not
// claimed before (the minimum over the part's symmetries); repeats are wrong.
evaluation::Score scorePoses(const std::vector<Eigen::Isometry3f>& poses,
                             const std::vector<simulation::ObjectTruth>& truth, const simulation::Part& part,
                             double diameter);
// "found F of N findable, D poses, matched objects: ..." for messages.
std::string describeScore(const evaluation::Score& score, std::size_t poses);

// Runs `method` on the scene's `input` cloud and scores it (symmetry-aware; repeats are wrong).
SceneOutcome runMethod(const PoseMethod& method, const BenchScene& scene, CloudInput input,
                       const simulation::Part& part, double diameter);

// Tallies by (input, part, method).
using TallyKey = std::tuple<CloudInput, std::string, std::string>;
using Tallies = std::map<TallyKey, Tally>;

// One CSV row per outcome, after writeOutcomeHeader.
void writeOutcomeHeader(std::ostream& out);
void writeOutcome(std::ostream& out, const SceneOutcome& outcome);

}  // namespace binpick::bench
