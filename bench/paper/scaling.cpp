#include "scaling.hpp"

#include <thread>

#include "bench_scenes.hpp"
#include "binpick/core/stopwatch.hpp"
#include "binpick/core/thread_count.hpp"
#include "binpick/estimation/detector.hpp"
#include "binpick/evaluation/evaluation.hpp"
#include "pose_method.hpp"

namespace binpick::bench {
namespace {

// The virtual rig with a sensor `width` pixels wide (5:4) behind a lens of the same field of view.
io::RigCalibration rigOfWidth(int width) {
  io::RigCalibration rig = simulation::makeVirtualRig();
  const double scale = static_cast<double>(width) / rig.camera.width;
  rig.camera.width = width;
  rig.camera.height = width * 4 / 5;
  rig.camera.fx *= scale;
  rig.camera.fy *= scale;
  rig.camera.cx = (rig.camera.width - 1) / 2.0;
  rig.camera.cy = (rig.camera.height - 1) / 2.0;
  return rig;
}

// Every second pixel of every second row: what a user would do to a cloud too big to handle.
io::PointCloud decimated(const io::PointCloud& cloud) {
  io::PointCloud out;
  out.width = (cloud.width + 1) / 2;
  out.height = (cloud.height + 1) / 2;
  out.points.reserve(static_cast<std::size_t>(out.width) * out.height);
  for (int y = 0; y < cloud.height; y += 2) {
    for (int x = 0; x < cloud.width; x += 2) {
      out.points.push_back(cloud.points[static_cast<std::size_t>(y) * cloud.width + x]);
    }
  }
  return out;
}

// Sums over scenes of one setting, turned into a ScalingPoint.
struct Accumulator {
  double input_points = 0, scene_points = 0, ms = 0, prepare_ms = 0;
  int objects = 0, correct = 0, scenes = 0;
  ScalingPoint point(const std::string& label, double x) const {
    ScalingPoint p;
    p.label = label;
    p.x = x;
    p.input_points = input_points / scenes;
    p.scene_points = scene_points / scenes;
    p.ms_per_scene = ms / scenes;
    p.ms_per_object = ms / objects;
    p.ms_scene_preparation = prepare_ms / scenes;
    p.recognition = static_cast<double>(correct) / objects;
    return p;
  }
};

estimation::Detector detectorWith(const estimation::PreparedModel& model, int objects, int threads) {
  estimation::DetectorParams params;
  params.selection.max_objects = objects;
  params.threads = threads;
  return estimation::Detector(model, params);
}

// Detects on the scene (decimating first when asked, inside the timed span) and adds it up.
void detectInto(const estimation::Detector& detector, const simulation::Part& part, const BenchScene& scene,
                bool decimate, Accumulator& acc) {
  const core::Stopwatch stopwatch;
  const io::PointCloud reduced = decimate ? decimated(scene.truth.cloud) : io::PointCloud{};
  const io::PointCloud& cloud = decimate ? reduced : scene.truth.cloud;
  const estimation::DetectionResult result = detector.detect(cloud, scene.crop);
  acc.ms += stopwatch.elapsedMs();
  acc.prepare_ms += result.timing_ms.prepare_scene;
  acc.input_points += static_cast<double>(croppedPoints({&cloud, scene.crop}).size());
  acc.scene_points += static_cast<double>(result.scene_points);
  acc.objects += static_cast<int>(scene.truth.objects.size());
  acc.correct += evaluation::scoreDetections(result.detections, scene.truth.objects, part.symmetry,
                                             {detector.model().diameter / 10.0, 10.0})
                     .correct;
  ++acc.scenes;
}

SceneRequest request(const ScalingParams& p, int objects, int scene_index, const io::RigCalibration& rig) {
  SceneRequest r;
  r.objects = objects;
  r.seed = p.seed + static_cast<uint64_t>(scene_index);
  r.reconstruct = false;
  r.rig = rig;
  return r;
}

void pointsScaling(const simulation::Part& part, const estimation::PreparedModel& model, const ScalingParams& p,
                   ScalingResults& out) {
  const estimation::Detector detector = detectorWith(model, p.objects, p.threads);
  for (int width : p.camera_widths) {
    const io::RigCalibration rig = rigOfWidth(width);
    Accumulator full, reduced;
    for (int s = 0; s < p.scenes; ++s) {
      const BenchScene scene = makeBenchScene(part, request(p, p.objects, s, rig));
      detectInto(detector, part, scene, false, full);
      detectInto(detector, part, scene, true, reduced);
    }
    const std::string size = std::to_string(width) + "x" + std::to_string(rig.camera.height);
    out.points_full.push_back(full.point(size, full.input_points / full.scenes));
    out.points_decimated.push_back(reduced.point(size + " decimated", reduced.input_points / reduced.scenes));
  }
}

void objectScaling(const simulation::Part& part, const estimation::PreparedModel& model, const ScalingParams& p,
                   ScalingResults& out) {
  for (int objects : p.object_counts) {
    const estimation::Detector detector = detectorWith(model, objects, p.threads);
    Accumulator acc;
    for (int s = 0; s < p.scenes; ++s) {
      detectInto(detector, part, makeBenchScene(part, request(p, objects, s, simulation::makeVirtualRig())), false,
                 acc);
    }
    out.objects.push_back(acc.point(std::to_string(objects) + " objects", objects));
  }
}

void threadScaling(const simulation::Part& part, const estimation::PreparedModel& model, const ScalingParams& p,
                   ScalingResults& out) {
  std::vector<BenchScene> scenes;
  for (int s = 0; s < p.scenes; ++s) {
    scenes.push_back(makeBenchScene(part, request(p, p.objects, s, simulation::makeVirtualRig())));
  }
  for (int threads : p.thread_counts) {
    const int resolved = core::resolveThreadCount(threads);
    const estimation::Detector detector = detectorWith(model, p.objects, resolved);
    Accumulator acc;
    for (const BenchScene& scene : scenes) detectInto(detector, part, scene, false, acc);
    const std::string label =
        std::to_string(resolved) + (resolved == 1 ? " thread" : " threads") + (threads == 0 ? " (all)" : "");
    out.threads.push_back(acc.point(label, resolved));
  }
}

}  // namespace

ScalingResults measureScaling(const simulation::Part& part, const estimation::PreparedModel& model,
                              const ScalingParams& params) {
  ScalingResults out;
  pointsScaling(part, model, params, out);
  objectScaling(part, model, params, out);
  threadScaling(part, model, params, out);
  return out;
}

}  // namespace binpick::bench
