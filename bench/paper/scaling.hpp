#pragma once
// How binpick's time scales: with the number of scene points (camera resolution, the cloud given
// whole or decimated first), with the number of objects in the bin, and with the thread count.
// Exact clouds, binpick's default parameters, one part.
#include <string>
#include <vector>

#include "binpick/estimation/model.hpp"
#include "binpick/simulation/parts.hpp"

namespace binpick::bench {

struct ScalingParams {
  std::vector<int> camera_widths{640, 1280, 1920, 2448};  // 5:4 sensors, same field of view
  std::vector<int> object_counts{5, 10, 20, 30, 40};
  std::vector<int> thread_counts{1, 2, 0};  // 0: all hardware threads
  int scenes = 2;                           // per setting
  int objects = 20;                         // where the count is not varied
  uint64_t seed = 1;
  int threads = 0;  // where the count is not varied
};

struct ScalingPoint {
  std::string label;          // the setting, e.g. "1280x1024 decimated", "20 objects", "2 threads"
  double x = 0.0;             // the varied quantity (input points, objects, threads)
  double input_points = 0.0;  // finite points in the bin, per scene
  double scene_points = 0.0;  // after binpick's subsampling, per scene
  double ms_per_scene = 0.0, ms_per_object = 0.0, ms_scene_preparation = 0.0;
  double recognition = 0.0;  // correct / objects
};

struct ScalingResults {
  std::vector<ScalingPoint> points_full, points_decimated, objects, threads;
};

ScalingResults measureScaling(const simulation::Part& part, const estimation::PreparedModel& model,
                              const ScalingParams& params);

}  // namespace binpick::bench
