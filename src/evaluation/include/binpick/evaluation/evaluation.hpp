#pragma once
// Scoring detections against the virtual cell's ground truth, shared by tests and benchmarks.
#include <Eigen/Geometry>
#include <vector>

#include "binpick/estimation/detector.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/pile.hpp"

namespace binpick::evaluation {

// The bin's inside, above its floor by `floor_margin` and inside the walls by `wall_margin`
// (metres), up to 0.1 m below the camera: the crop a cell would configure.
estimation::CropBox binInterior(const simulation::PileScene& scene, const simulation::PileParams& params,
                                double floor_margin = 0.003, double wall_margin = 0.003);

struct Thresholds {
  double translation = 0.0;    // the paper: diam(M) / 10
  double rotation_deg = 10.0;  // the paper: 10 degrees
};

struct Score {
  int findable = 0;  // objects at least `min_visible` visible
  int found = 0;     // findable objects matched by a detection
  int correct = 0;   // detections matching an object not matched before
  int wrong = 0;     // detections matching nothing, or an object matched before
  int wrong_in_first_10 = 0;
  std::vector<int> matched_object;  // per detection: object index or -1
};

// Detections in order; each is correct when it lies within the thresholds of an object not yet
// claimed (symmetry-aware); repeats count as wrong, as in the paper.
Score scoreDetections(const std::vector<estimation::Detection>& detections,
                      const std::vector<simulation::ObjectTruth>& truth, const simulation::Symmetry& symmetry,
                      const Thresholds& thresholds, double min_visible = 0.5);

}  // namespace binpick::evaluation
