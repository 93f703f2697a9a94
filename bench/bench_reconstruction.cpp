// Reconstruction benchmark on virtual-cell piles:
// 1. speed of each stage (decode, triangulate, filter) and of the whole reconstruct, from images
//    already in memory, for the virtual rig's 1280x1024 camera and a 2448x2048 one;
// 2. accuracy of the reconstructed cloud against the cell's exact depth;
// 3. end-to-end detection on the reconstructed cloud versus the ideal sensor's and the exact one;
// 4. (--pattern-sets) the images each candidate pattern set takes, the capture time they imply,
//    and the coverage and accuracy they give.
//
//   bench_reconstruction [--part l_bracket] [--parts l_bracket,clamp,gear,ring_magnet]
//                        [--scenes 3] [--repeats 15] [--threads 0] [--skip-large] [--skip-detection]
//                        [--lighting clean|harsh] [--mixed-pixels K] [--camera-blur SIGMA]
//                        [--settings FILE] [--pattern-sets]
// --pattern-sets runs only section 4: candidate pattern sets (fewer images: columns only, a
// complementary Gray code, no inverses) on the same piles, against the default set.
// --settings reads the `reconstruction:` section of a settings file (defaults otherwise).
// --lighting picks the virtual cell's photometry preset (lighting_presets.hpp) for every capture.
// --mixed-pixels sets its mixed_pixel_samples (K x K rays over each pixel at depth edges; 1: one
// ray per pixel, no mixed pixels; default: the preset's), --camera-blur its camera_blur_sigma
// (pixels).
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "binpick/core/error.hpp"
#include "binpick/core/stopwatch.hpp"
#include "binpick/core/thread_count.hpp"
#include "binpick/estimation/detector.hpp"
#include "binpick/evaluation/evaluation.hpp"
#include "binpick/reconstruction/reconstruction.hpp"
#include "binpick/reconstruction/reconstruction_config.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/pile.hpp"
#include "binpick/simulation/virtual_rig.hpp"
#include "sensor/lighting_presets.hpp"

namespace {

using namespace binpick;

constexpr int kObjects = 20;
constexpr double kWrongMm = 5.0;     // a point this far off in z is a wrong point, not noise
constexpr double kEdgeStepMm = 3.0;  // adjacent truth depths this far apart: a depth edge
constexpr int kEdgeRadius = 2;       // pixels: "near a depth edge"
constexpr double kPi = 3.14159265358979323846;

struct Options {
  std::string part = "l_bracket";
  std::vector<std::string> parts{"l_bracket", "clamp", "gear", "ring_magnet"};
  int scenes = 3;
  int repeats = 15;
  int threads = 0;
  bool skip_large = false;
  bool skip_detection = false;
  bool pattern_sets = false;
  std::string lighting = "clean";
  int mixed_pixels = 0;      // 0: the preset's mixed_pixel_samples
  double camera_blur = NAN;  // NaN: the preset's camera_blur_sigma
  std::string settings;      // empty: reconstruction defaults
};

using bench::splitCommas;

// The photometry preset with the options' overrides.
simulation::PhotometryParams photometryFor(const Options& o) {
  simulation::PhotometryParams p = simulation::photometryPreset(o.lighting);
  if (o.mixed_pixels > 0) p.mixed_pixel_samples = o.mixed_pixels;
  if (!std::isnan(o.camera_blur)) p.camera_blur_sigma = o.camera_blur;
  p.validate();
  return p;
}

int positiveCount(const std::string& flag, const std::string& value) {
  const int n = std::stoi(value);
  if (n < 1) throw core::Error("bench_reconstruction: " + flag + " must be >= 1 (got " + value + ")");
  return n;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--skip-large") {
      o.skip_large = true;
      continue;
    }
    if (flag == "--skip-detection") {
      o.skip_detection = true;
      continue;
    }
    if (flag == "--pattern-sets") {
      o.pattern_sets = true;
      continue;
    }
    if (i + 1 >= argc) throw core::Error("bench_reconstruction: " + flag + " needs a value");
    const std::string value = argv[++i];
    if (flag == "--part")
      o.part = value;
    else if (flag == "--parts")
      o.parts = splitCommas(value);
    else if (flag == "--scenes")
      o.scenes = std::stoi(value);
    else if (flag == "--repeats")
      o.repeats = std::stoi(value);
    else if (flag == "--threads")
      o.threads = std::stoi(value);
    else if (flag == "--lighting")
      o.lighting = value;
    else if (flag == "--mixed-pixels")
      o.mixed_pixels = positiveCount(flag, value);
    else if (flag == "--camera-blur")
      o.camera_blur = std::stod(value);
    else if (flag == "--settings")
      o.settings = value;
    else
      throw core::Error("bench_reconstruction: unknown option " + flag);
  }
  if (o.scenes < 1 || o.repeats < 1) throw core::Error("bench_reconstruction: --scenes and --repeats must be >= 1");
  if (o.threads < 0) throw core::Error("bench_reconstruction: --threads must be >= 0");
  photometryFor(o);  // an unknown preset or a bad override fails here, before any rendering
  return o;
}

// ---------------------------------------------------------------------------------------------
// Rendering (setup, not measured).

// The virtual rig with a 5 MP sensor behind a lens of the same field of view: the focal length
// scales with the sensor width (2448 / 1280 = 1.9125) and the distortion, being in normalised
// coordinates, stays the same.
io::RigCalibration largeRig() {
  io::RigCalibration rig = simulation::makeVirtualRig();
  rig.camera.width = 2448;
  rig.camera.height = 2048;
  rig.camera.fx = rig.camera.fy = 1600.0 * 1.9125;
  rig.camera.cx = (2448 - 1) / 2.0;
  rig.camera.cy = (2048 - 1) / 2.0;
  return rig;
}

struct RenderedPile {
  simulation::PileParams params;
  simulation::PileScene scene;
  io::Capture capture;
};

// The default pattern set (Gray code columns + rows, 4 phase steps) for the rig's projector.
io::PatternSetSpec defaultPatterns(const io::RigCalibration& rig) {
  io::PatternSetSpec patterns;
  patterns.projector_width = rig.projector.width;
  patterns.projector_height = rig.projector.height;
  return patterns;
}

RenderedPile renderPile(const simulation::Part& part, const io::RigCalibration& rig, uint64_t seed, const Options& o,
                        const io::PatternSetSpec& patterns) {
  RenderedPile r;
  r.params.objects = kObjects;
  r.params.seed = seed;
  r.params.rig = rig;
  simulation::PhotometryParams photometry = photometryFor(o);
  photometry.seed = seed;
  simulation::PileCapture pile = simulation::generatePileCapture(part.mesh, r.params, patterns, photometry);
  r.scene = std::move(pile.scene);
  r.capture = simulation::recordedCapture(std::move(pile.images), r.params, patterns, photometry,
                                          "bench_reconstruction " + part.name);
  return r;
}

reconstruction::ReconstructionParams reconstructionParams(const Options& o) {
  reconstruction::ReconstructionParams p = o.settings.empty() ? reconstruction::ReconstructionParams{}
                                                              : reconstruction::loadReconstructionParams(o.settings);
  p.setThreads(o.threads);
  return p;
}

// ---------------------------------------------------------------------------------------------
// 1. Speed.

struct Timing {
  double median = std::numeric_limits<double>::quiet_NaN();
  double min = std::numeric_limits<double>::quiet_NaN();
  // The process's CPU time per run (all threads): on a machine shared with other work the wall
  // time varies by 2x and more, the CPU time far less.
  double cpu_median = std::numeric_limits<double>::quiet_NaN();
  double cpu_min = std::numeric_limits<double>::quiet_NaN();
};

// User + system CPU time of the whole process so far, milliseconds.
double processCpuMs() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto ms = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_usec) / 1e3;
  };
  return ms(usage.ru_utime) + ms(usage.ru_stime);
}

// One untimed warm-up (first-touch allocations, OpenMP pool start-up), then `repeats` timed runs;
// `setup` runs before each and is not timed (e.g. a fresh copy for a stage that works in place).
template <typename Setup, typename Run>
Timing timeRuns(int repeats, Setup setup, Run run) {
  setup();
  run();
  std::vector<double> ms, cpu;
  for (int i = 0; i < repeats; ++i) {
    setup();
    const double cpu_start = processCpuMs();
    const core::Stopwatch stopwatch;
    run();
    ms.push_back(stopwatch.elapsedMs());
    cpu.push_back(processCpuMs() - cpu_start);
  }
  std::sort(ms.begin(), ms.end());
  std::sort(cpu.begin(), cpu.end());
  return {ms[ms.size() / 2], ms.front(), cpu[cpu.size() / 2], cpu.front()};
}

template <typename Run>
Timing timeRuns(int repeats, Run run) {
  return timeRuns(
      repeats, [] {}, run);
}

struct SpeedResult {
  std::string name;  // "1280x1024"
  Timing setup, decode, triangulate, filter, reconstruct;
};

// Each stage is timed on its own, from the previous stage's output computed once, so that the
// stage numbers do not include each other; the whole reconstruct is timed separately.
SpeedResult measureSpeed(const io::RigCalibration& rig, const io::Capture& capture, const Options& o,
                         reconstruction::Reconstruction& result) {
  namespace rc = reconstruction;
  const rc::ReconstructionParams params = reconstructionParams(o);
  SpeedResult s;
  s.name = std::to_string(rig.camera.width) + "x" + std::to_string(rig.camera.height);
  s.setup = timeRuns(o.repeats, [&] { const rc::Triangulator t(rig, params.triangulation); });
  const rc::Triangulator triangulator(rig, params.triangulation);
  rc::DecodedCapture decoded;
  s.decode = timeRuns(o.repeats, [&] { decoded = rc::decodeCapture(capture, params.decode); });
  rc::TriangulatedCloud triangulated;
  s.triangulate = timeRuns(o.repeats, [&] { triangulated = triangulator.triangulate(decoded); });
  io::PointCloud cloud;
  cv::Mat status;
  s.filter = timeRuns(
      o.repeats,
      [&] {
        cloud = triangulated.cloud;
        status = triangulated.status.clone();
      },
      [&] { rc::filterCloud(cloud, status, params.filter); });
  const rc::Reconstructor reconstructor(rig, params);
  s.reconstruct = timeRuns(o.repeats, [&] { result = reconstructor.reconstruct(capture); });
  return s;
}

void printTimingRow(const char* label, const std::vector<SpeedResult>& results, Timing SpeedResult::*field) {
  std::printf("  %-28s", label);
  for (const SpeedResult& r : results) std::printf(" %9.1f %9.1f", (r.*field).median, (r.*field).min);
  std::printf("\n");
}

void printSpeed(const std::vector<SpeedResult>& results, const Options& o) {
  std::printf("\n== 1. Speed (ms, from images in memory; median and min of %d runs after 1 warm-up) ==\n", o.repeats);
  std::printf("  %-28s", "capture");
  for (const SpeedResult& r : results) std::printf(" %19s", r.name.c_str());
  std::printf("\n  %-28s", "");
  for (std::size_t i = 0; i < results.size(); ++i) std::printf(" %9s %9s", "median", "min");
  std::printf("\n");
  printTimingRow("Triangulator setup (once)", results, &SpeedResult::setup);
  printTimingRow("decode", results, &SpeedResult::decode);
  printTimingRow("triangulate", results, &SpeedResult::triangulate);
  printTimingRow("filter", results, &SpeedResult::filter);
  std::printf("  %-28s", "sum of the three (medians)");
  for (const SpeedResult& r : results) {
    std::printf(" %9.1f %9s", r.decode.median + r.triangulate.median + r.filter.median, "");
  }
  std::printf("\n");
  printTimingRow("reconstruct (whole)", results, &SpeedResult::reconstruct);
  std::printf("  %-28s", "reconstruct, CPU (threads)");
  for (const SpeedResult& r : results) std::printf(" %9.1f %9.1f", r.reconstruct.cpu_median, r.reconstruct.cpu_min);
  std::printf("\n");
}

// ---------------------------------------------------------------------------------------------
// 2. Accuracy.

struct ErrorStats {
  std::size_t count = 0;
  double median = NAN, p90 = NAN, p95 = NAN, p99 = NAN;  // |dz|, mm
  double bias = NAN;                                     // median signed dz (reconstructed - true), mm
  std::size_t wrong = 0;                                 // |dz| > kWrongMm
};

double quantile(const std::vector<double>& sorted, double q) {
  return sorted[static_cast<std::size_t>(q * static_cast<double>(sorted.size() - 1) + 0.5)];
}

ErrorStats errorStats(std::vector<double> signed_mm) {
  ErrorStats s;
  s.count = signed_mm.size();
  if (signed_mm.empty()) return s;
  std::vector<double> abs_mm;
  for (const double e : signed_mm) abs_mm.push_back(std::abs(e));
  std::sort(abs_mm.begin(), abs_mm.end());
  std::sort(signed_mm.begin(), signed_mm.end());
  s.median = quantile(abs_mm, 0.5);
  s.p90 = quantile(abs_mm, 0.9);
  s.p95 = quantile(abs_mm, 0.95);
  s.p99 = quantile(abs_mm, 0.99);
  s.bias = quantile(signed_mm, 0.5);
  s.wrong = static_cast<std::size_t>(abs_mm.end() - std::upper_bound(abs_mm.begin(), abs_mm.end(), kWrongMm));
  return s;
}

// Whether a truth depth edge (adjacent pixels more than kEdgeStepMm apart, or one of them seeing
// nothing) lies within kEdgeRadius pixels: wrong points there are mixed or misdecoded edge pixels,
// elsewhere they point at a decoding problem on smooth surfaces.
bool nearDepthEdge(const simulation::PileScene& scene, int x, int y) {
  const int w = scene.cloud.width, h = scene.cloud.height;
  const auto step = [&](int x0, int y0, int x1, int y1) {
    if (x1 >= w || y1 >= h) return false;
    const float a = scene.depth[static_cast<std::size_t>(y0) * w + x0];
    const float b = scene.depth[static_cast<std::size_t>(y1) * w + x1];
    return std::isfinite(a) != std::isfinite(b) || std::abs(a - b) * 1000.0 > kEdgeStepMm;
  };
  for (int v = std::max(0, y - kEdgeRadius); v <= std::min(h - 1, y + kEdgeRadius); ++v) {
    for (int u = std::max(0, x - kEdgeRadius); u <= std::min(w - 1, x + kEdgeRadius); ++u) {
      if (step(u, v, u + 1, v) || step(u, v, u, v + 1)) return true;
    }
  }
  return false;
}

// Why the ideal sensor has no point where the reconstruction has one.
enum class ExtraKind { Grazing, Unlit, NothingSeen };

ExtraKind extraKind(const simulation::PileScene& scene, const simulation::PileParams& params, std::size_t i) {
  const Eigen::Vector3f p = scene.exact_cloud.points[i];
  if (!p.allFinite()) return ExtraKind::NothingSeen;
  const float cos_view = -scene.exact_cloud.normals[i].dot(p.normalized());
  const bool grazing = cos_view < static_cast<float>(std::cos(params.max_view_angle_deg * kPi / 180.0));
  return grazing ? ExtraKind::Grazing : ExtraKind::Unlit;
}

struct Accuracy {
  std::string name;
  // Valid points farther than kWrongMm from every surface point the camera sees (flying points:
  // mixed pixels at depth edges, misdecoded points), and of those, where the pixel's own ray sees
  // a surface the projector does not light (projector shadow), or nothing.
  std::size_t off_surfaces = 0, off_surfaces_unlit = 0, off_surfaces_nothing = 0;
  std::size_t ideal = 0;        // pixels where scene.cloud is finite
  std::size_t valid_ideal = 0;  // of those, valid in the reconstruction
  ErrorStats all;               // every valid pixel with a true depth
  std::size_t wrong_near_edge = 0;
  ErrorStats extra;  // valid pixels where scene.cloud is NaN
  std::size_t extra_grazing = 0, extra_unlit = 0, extra_nothing = 0;
  std::size_t extra_on_bin = 0;            // instance -2: the bin's walls and floor rather than parts
  ErrorStats ideal_sensor;                 // scene.cloud itself against the truth: the noise floor
  reconstruction::StatusCounts missing{};  // ideal pixels the reconstruction lacks, by status
  std::size_t parts_ideal = 0;             // ideal pixels on the parts (instance >= 0)
  std::size_t parts_valid = 0;             // of those, valid in the reconstruction
  reconstruction::StatusCounts parts_missing{};
};

double zErrorMm(const Eigen::Vector3f& point, float true_z) {
  return (static_cast<double>(point.z()) - static_cast<double>(true_z)) * 1000.0;
}

void countWrongNearEdges(const simulation::PileScene& scene, const io::PointCloud& cloud, Accuracy& a) {
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    const Eigen::Vector3f p = cloud.points[i];
    if (!p.allFinite() || !std::isfinite(scene.depth[i]) || std::abs(zErrorMm(p, scene.depth[i])) <= kWrongMm) {
      continue;
    }
    const int x = static_cast<int>(i % static_cast<std::size_t>(cloud.width));
    const int y = static_cast<int>(i / static_cast<std::size_t>(cloud.width));
    a.wrong_near_edge += nearDepthEdge(scene, x, y) ? 1 : 0;
  }
}

// Whether `p` (seen through pixel `i`) lies farther than kWrongMm from every surface point the
// camera sees (scene.exact_cloud, one per pixel centre). A surface point that close projects
// within f * kWrongMm / (z - kWrongMm) pixels of pixel i: only those are looked at.
bool offEverySurface(const simulation::PileScene& scene, std::size_t i, const Eigen::Vector3f& p) {
  const io::PointCloud& exact = scene.exact_cloud;
  const float reach = static_cast<float>(kWrongMm / 1000.0);
  if ((exact.points[i] - p).norm() <= reach) return false;  // the common case: its own surface
  if (!(p.z() > 2.0f * reach)) return true;
  const int radius = static_cast<int>(std::ceil(scene.rig.camera.fx * reach / (p.z() - reach))) + 1;
  const int x = static_cast<int>(i % static_cast<std::size_t>(exact.width));
  const int y = static_cast<int>(i / static_cast<std::size_t>(exact.width));
  for (int v = std::max(0, y - radius); v <= std::min(exact.height - 1, y + radius); ++v) {
    for (int u = std::max(0, x - radius); u <= std::min(exact.width - 1, x + radius); ++u) {
      const Eigen::Vector3f& q = exact.points[static_cast<std::size_t>(v) * exact.width + u];
      if (q.allFinite() && (q - p).norm() <= reach) return false;
    }
  }
  return true;
}

void countOffSurfaces(const RenderedPile& pile, const io::PointCloud& cloud, Accuracy& a) {
  const simulation::PileScene& scene = pile.scene;
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    const Eigen::Vector3f p = cloud.points[i];
    if (!p.allFinite() || !offEverySurface(scene, i, p)) continue;
    ++a.off_surfaces;
    if (scene.cloud.points[i].allFinite()) continue;  // the ideal sensor measures the pixel
    const ExtraKind kind = extraKind(scene, pile.params, i);
    a.off_surfaces_nothing += kind == ExtraKind::NothingSeen ? 1 : 0;
    a.off_surfaces_unlit += kind == ExtraKind::Unlit ? 1 : 0;
  }
}

Accuracy measureAccuracy(const std::string& name, const RenderedPile& pile, const reconstruction::Reconstruction& r) {
  const simulation::PileScene& scene = pile.scene;
  Accuracy a;
  a.name = name;
  // The status image is indexed like the cloud: make sure it is one block.
  const cv::Mat status = r.status.isContinuous() ? r.status : r.status.clone();
  std::vector<double> all, extra, ideal;
  for (std::size_t i = 0; i < r.cloud.points.size(); ++i) {
    const Eigen::Vector3f p = r.cloud.points[i];
    const bool measurable = scene.cloud.points[i].allFinite();
    const bool valid = p.allFinite();
    a.ideal += measurable ? 1 : 0;
    a.valid_ideal += measurable && valid ? 1 : 0;
    if (measurable && !valid) ++a.missing[status.data[i]];
    const bool on_part = measurable && scene.instance[i] >= 0;
    a.parts_ideal += on_part ? 1 : 0;
    a.parts_valid += on_part && valid ? 1 : 0;
    if (on_part && !valid) ++a.parts_missing[status.data[i]];
    if (measurable) ideal.push_back(zErrorMm(scene.cloud.points[i], scene.depth[i]));
    if (!valid || !std::isfinite(scene.depth[i])) continue;
    all.push_back(zErrorMm(p, scene.depth[i]));
    if (measurable) continue;
    extra.push_back(all.back());
    const ExtraKind kind = extraKind(scene, pile.params, i);
    a.extra_grazing += kind == ExtraKind::Grazing ? 1 : 0;
    a.extra_unlit += kind == ExtraKind::Unlit ? 1 : 0;
    a.extra_on_bin += scene.instance[i] == -2 ? 1 : 0;
  }
  // Valid points where nothing was seen have no true depth, so they are counted apart.
  for (std::size_t i = 0; i < r.cloud.points.size(); ++i) {
    a.extra_nothing += r.cloud.points[i].allFinite() && !std::isfinite(scene.depth[i]) ? 1 : 0;
  }
  a.all = errorStats(std::move(all));
  a.extra = errorStats(std::move(extra));
  a.ideal_sensor = errorStats(std::move(ideal));
  countWrongNearEdges(scene, r.cloud, a);
  countOffSurfaces(pile, r.cloud, a);
  return a;
}

template <typename Format>
void printAccuracyRow(const char* label, const std::vector<Accuracy>& results, Format format) {
  std::printf("  %-44s", label);
  for (const Accuracy& a : results) std::printf(" %26s", format(a).c_str());
  std::printf("\n");
}

std::string fmt(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

std::string countText(std::size_t n) { return std::to_string(n); }

std::string triple(const ErrorStats& s) {
  return fmt("%.2f", s.median) + " " + fmt("%.2f", s.p90) + " " + fmt("%.1f", s.p99);
}

void printStatusCounts(const std::string& title, const reconstruction::StatusCounts& counts) {
  std::printf("  %s:", title.c_str());
  for (std::size_t s = 1; s < reconstruction::kPixelStatusCount; ++s) {
    if (counts[s] == 0) continue;
    std::printf(" %s %zu", reconstruction::statusName(static_cast<reconstruction::PixelStatus>(s)), counts[s]);
  }
  std::printf("\n");
}

void printMissing(const std::vector<Accuracy>& results) {
  for (const Accuracy& a : results) {
    printStatusCounts(a.name + ", ideal-sensor pixels without a point, by status", a.missing);
    printStatusCounts(a.name + ", parts' pixels without a point, by status", a.parts_missing);
  }
}

void printAccuracy(const std::vector<Accuracy>& r, const std::string& part, const std::string& lighting) {
  std::printf(
      "\n== 2. Accuracy against the virtual cell's truth (%s, %d objects, seed 1, %s lighting; dz = z_rec - z_true) "
      "==\n",
      part.c_str(), kObjects, lighting.c_str());
  printAccuracyRow("capture", r, [](const Accuracy& a) { return a.name; });
  printAccuracyRow("ideal-sensor pixels (scene.cloud finite)", r, [](const Accuracy& a) { return countText(a.ideal); });
  printAccuracyRow("  valid in reconstruction", r, [](const Accuracy& a) {
    return fmt("%.2f%%", 100.0 * static_cast<double>(a.valid_ideal) / static_cast<double>(a.ideal));
  });
  printAccuracyRow("parts' pixels (ideal sensor, on a part)", r,
                   [](const Accuracy& a) { return countText(a.parts_ideal); });
  printAccuracyRow("  valid in reconstruction (coverage)", r, [](const Accuracy& a) {
    return fmt("%.2f%%", 100.0 * static_cast<double>(a.parts_valid) / static_cast<double>(a.parts_ideal));
  });
  printAccuracyRow("valid points with a true depth", r, [](const Accuracy& a) { return countText(a.all.count); });
  printAccuracyRow("  |dz| median / p90 / p99, mm", r, [](const Accuracy& a) { return triple(a.all); });
  printAccuracyRow("  |dz| p95, mm", r, [](const Accuracy& a) { return fmt("%.2f", a.all.p95); });
  printAccuracyRow("  median signed dz (bias), mm", r, [](const Accuracy& a) { return fmt("%+.3f", a.all.bias); });
  printAccuracyRow("  wrong (|dz| > 5 mm)", r, [](const Accuracy& a) { return countText(a.all.wrong); });
  printAccuracyRow("    of which within 2 px of a depth edge", r,
                   [](const Accuracy& a) { return countText(a.wrong_near_edge); });
  printAccuracyRow("valid where scene.cloud is NaN (extra)", r,
                   [](const Accuracy& a) { return countText(a.extra.count); });
  printAccuracyRow("  grazing (view angle > 80 deg)", r, [](const Accuracy& a) { return countText(a.extra_grazing); });
  printAccuracyRow("  not grazing (truth: unlit)", r, [](const Accuracy& a) { return countText(a.extra_unlit); });
  printAccuracyRow("  on the bin (not on parts)", r, [](const Accuracy& a) { return countText(a.extra_on_bin); });
  printAccuracyRow("  |dz| median / p90 / p99, mm", r, [](const Accuracy& a) { return triple(a.extra); });
  printAccuracyRow("  wrong (|dz| > 5 mm)", r, [](const Accuracy& a) { return countText(a.extra.wrong); });
  printAccuracyRow("flying: > 5 mm from every surface seen", r,
                   [](const Accuracy& a) { return countText(a.off_surfaces); });
  printAccuracyRow("  where the pixel sees an unlit surface", r,
                   [](const Accuracy& a) { return countText(a.off_surfaces_unlit); });
  printAccuracyRow("  where the pixel sees nothing", r,
                   [](const Accuracy& a) { return countText(a.off_surfaces_nothing); });
  printAccuracyRow("valid where nothing is seen (no truth)", r,
                   [](const Accuracy& a) { return countText(a.extra_nothing); });
  printAccuracyRow("ideal sensor itself: |dz| med / p90 / p99", r,
                   [](const Accuracy& a) { return triple(a.ideal_sensor); });
  printMissing(r);
}

// ---------------------------------------------------------------------------------------------
// 3. End-to-end detection.

struct CloudTotals {
  int findable = 0, found = 0, wrong_first_10 = 0;
  double ms = 0.0;
  std::size_t points = 0;
};

std::size_t validPoints(const io::PointCloud& cloud) {
  std::size_t n = 0;
  for (const auto& p : cloud.points) n += p.allFinite() ? 1 : 0;
  return n;
}

void detectInto(const estimation::Detector& detector, const io::PointCloud& cloud, const simulation::PileScene& scene,
                const simulation::Part& part, CloudTotals& totals) {
  const estimation::DetectionResult result = detector.detect(cloud);
  const evaluation::Score score = evaluation::scoreDetections(result.detections, scene.objects, part.symmetry,
                                                              {detector.model().diameter / 10.0, 10.0});
  totals.findable += score.findable;
  totals.found += score.found;
  totals.wrong_first_10 += score.wrong_in_first_10;
  totals.ms += result.timing_ms.total;
  totals.points += validPoints(cloud);
}

void printDetectionRow(const char* label, const CloudTotals& t, const Options& o) {
  const double objects = static_cast<double>(o.scenes) * kObjects;
  std::printf("  %-26s %8.0fk %8.1f%% %3d/%-3d %10d %12.1f\n", label, static_cast<double>(t.points) / 1000.0 / o.scenes,
              t.findable ? 100.0 * t.found / t.findable : 0.0, t.found, t.findable, t.wrong_first_10, t.ms / objects);
}

// The detector on the same pile seen three ways: through the whole reconstruction, through the
// ideal sensor and as exact geometry; the gaps between them are what reconstruction costs.
void benchDetectionPart(const std::string& part_name, const reconstruction::Reconstructor& reconstructor,
                        const Options& o) {
  const simulation::Part part = simulation::makePart(part_name);
  const estimation::PreparedModel model = estimation::prepareModel(io::ModelGeometry{part.mesh, {}}, {});
  estimation::DetectorParams params;
  params.selection.max_objects = kObjects;
  params.threads = o.threads;
  CloudTotals reconstructed, ideal, exact;
  for (int s = 1; s <= o.scenes; ++s) {
    const RenderedPile pile =
        renderPile(part, reconstructor.rig(), static_cast<uint64_t>(s), o, defaultPatterns(reconstructor.rig()));
    params.scene.crop = evaluation::binInterior(pile.scene, pile.params);
    const estimation::Detector detector(model, params);
    detectInto(detector, reconstructor.reconstruct(pile.capture).cloud, pile.scene, part, reconstructed);
    detectInto(detector, pile.scene.cloud, pile.scene, part, ideal);
    detectInto(detector, pile.scene.exact_cloud, pile.scene, part, exact);
  }
  std::printf("%s\n", part_name.c_str());
  printDetectionRow("(a) reconstructed", reconstructed, o);
  printDetectionRow("(b) ideal (scene.cloud)", ideal, o);
  printDetectionRow("(c) exact (exact_cloud)", exact, o);
}

void benchDetection(const Options& o) {
  std::printf(
      "\n== 3. End-to-end detection (%d scenes x %d objects, seeds 1..%d, 1280x1024; "
      "correct: < diam/10 and 10 deg) ==\n",
      o.scenes, kObjects, o.scenes);
  std::printf("  %-26s %9s %17s %10s %12s\n", "cloud", "pts/scene", "recognition", "wrong@10", "ms/object");
  const reconstruction::Reconstructor reconstructor(simulation::makeVirtualRig(), reconstructionParams(o));
  for (const std::string& part : o.parts) benchDetectionPart(part, reconstructor, o);
  std::printf(
      "  (recognition: found / objects >= 50%% visible; wrong@10: wrong among the first 10 "
      "detections, summed over scenes)\n");
}

// ---------------------------------------------------------------------------------------------

// ---------------------------------------------------------------------------------------------
// 4. Pattern sets.

// 1280x1024 Mono8 frames on 1 Gb/s GigE Vision: about 95 per second, whatever the exposure.
constexpr double kGigEFramesPerSecond = 95.0;

struct PatternSetCandidate {
  std::string name;
  io::PatternSetSpec spec;
  bool inverses = true;  // false: the Gray bits' inverses are left out (thresholds from white and black)
};

std::vector<PatternSetCandidate> patternSetCandidates(const io::RigCalibration& rig) {
  const auto candidate = [&](const char* name, bool rows, int period, int gray_unit, bool inverses) {
    io::PatternSetSpec spec = defaultPatterns(rig);
    spec.row_codes = rows;
    spec.phase_period = period;
    spec.gray_unit = gray_unit;
    return PatternSetCandidate{name, spec, inverses};
  };
  return {candidate("default: Gray cols+rows, 4-step P16", true, 16, 0, true),
          candidate("Gray cols, 4-step P16", false, 16, 0, true),
          candidate("compl. Gray cols+rows, 4-step P16", true, 16, 8, true),
          candidate("compl. Gray cols, 4-step P16", false, 16, 8, true),
          candidate("compl. Gray cols, 4-step P32", false, 32, 16, true),
          candidate("compl. Gray cols no inv, 4-step P16", false, 16, 8, false)};
}

io::Capture withoutInverses(const io::Capture& capture) {
  io::Capture kept;
  kept.metadata = capture.metadata;
  kept.metadata.patterns.clear();
  kept.metadata.images.clear();  // a capture in memory: its file names are made when written
  for (std::size_t i = 0; i < capture.images.size(); ++i) {
    const std::string& name = capture.metadata.patterns[i];
    if (name.size() > 4 && name.compare(name.size() - 4, 4, "_inv") == 0) continue;
    kept.images.push_back(capture.images[i]);
    kept.metadata.patterns.push_back(name);
  }
  return kept;
}

struct PatternSetTotals {
  std::size_t images = 0;
  std::size_t parts_ideal = 0, parts_valid = 0, wrong = 0;
  std::vector<double> medians;  // |dz| per capture, mm
  double reconstruct_ms = 0.0;
  reconstruction::StatusCounts parts_missing{};
};

void printPatternSets(const std::vector<PatternSetCandidate>& candidates, const std::vector<PatternSetTotals>& totals,
                      int captures) {
  std::printf("  %-38s %6s %9s %9s %10s %8s %12s\n", "pattern set", "images", "capture", "coverage", "|dz| med",
              "wrong", "reconstruct");
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const PatternSetTotals& t = totals[c];
    std::vector<double> medians = t.medians;
    std::sort(medians.begin(), medians.end());
    std::printf(
        "  %-38s %6zu %7.0fms %8.1f%% %8.3fmm %8zu %10.0fms\n", candidates[c].name.c_str(), t.images,
        1000.0 * static_cast<double>(t.images) / kGigEFramesPerSecond,
        100.0 * static_cast<double>(t.parts_valid) / static_cast<double>(std::max<std::size_t>(t.parts_ideal, 1)),
        medians.empty() ? NAN : medians[medians.size() / 2], t.wrong, t.reconstruct_ms / captures);
  }
  std::printf(
      "  (capture: images at %.0f frames/s, GigE Vision 1280x1024 Mono8; coverage: the parts' pixels the ideal "
      "sensor sees that get a point; |dz| med: median over captures of each one's median; wrong: points > %.0f mm "
      "off in z, summed; reconstruct: mean per capture)\n",
      kGigEFramesPerSecond, kWrongMm);
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    printStatusCounts(candidates[c].name + ", parts' pixels without a point", totals[c].parts_missing);
  }
}

// Every candidate set on the same piles (the parts of --parts, seeds 1..--scenes, the options'
// lighting), reconstructed with the same settings.
void benchPatternSets(const Options& o) {
  const io::RigCalibration rig = simulation::makeVirtualRig();
  const std::vector<PatternSetCandidate> candidates = patternSetCandidates(rig);
  std::vector<PatternSetTotals> totals(candidates.size());
  const reconstruction::Reconstructor reconstructor(rig, reconstructionParams(o));
  int captures = 0;
  for (const std::string& part_name : o.parts) {
    const simulation::Part part = simulation::makePart(part_name);
    for (int seed = 1; seed <= o.scenes; ++seed, ++captures) {
      const RenderedPile pile = renderPile(part, rig, static_cast<uint64_t>(seed), o, candidates.front().spec);
      simulation::PhotometryParams photometry = photometryFor(o);
      photometry.seed = static_cast<uint64_t>(seed);
      if (captures == 0) reconstructor.reconstruct(pile.capture);  // warm-up: first-touch allocations, threads
      for (std::size_t c = 0; c < candidates.size(); ++c) {
        const io::PatternSetSpec& spec = candidates[c].spec;
        io::Capture capture =
            c == 0 ? pile.capture
                   : simulation::recordedCapture(
                         simulation::renderPileImages(part.mesh, pile.scene, pile.params, spec, photometry),
                         pile.params, spec, photometry, "bench_reconstruction " + part_name);
        if (!candidates[c].inverses) capture = withoutInverses(capture);
        const core::Stopwatch stopwatch;
        const reconstruction::Reconstruction result = reconstructor.reconstruct(capture);
        totals[c].reconstruct_ms += stopwatch.elapsedMs();
        const Accuracy a = measureAccuracy(candidates[c].name, pile, result);
        totals[c].images = capture.images.size();
        totals[c].parts_ideal += a.parts_ideal;
        totals[c].parts_valid += a.parts_valid;
        totals[c].wrong += a.all.wrong;
        totals[c].medians.push_back(a.all.median);
        for (std::size_t k = 0; k < a.parts_missing.size(); ++k) totals[c].parts_missing[k] += a.parts_missing[k];
      }
      std::fprintf(stderr, "  %s seed %d done\n", part_name.c_str(), seed);
    }
  }
  std::printf("\n== 4. Pattern sets (%s lighting, %zu parts x %d scenes x %d objects, 1280x1024) ==\n",
              o.lighting.c_str(), o.parts.size(), o.scenes, kObjects);
  printPatternSets(candidates, totals, captures);
}

// What tracing mixed pixels costs: the pile's images rendered again (rays cast again too) with
// one ray per pixel and with the options' mixed pixels, each timed once.
void printMixedPixelCost(const simulation::Part& part, const RenderedPile& pile, const Options& o) {
  simulation::PhotometryParams mixed = photometryFor(o);
  if (mixed.mixed_pixel_samples <= 1) return;
  simulation::PhotometryParams one_ray = mixed;
  one_ray.mixed_pixel_samples = 1;
  const io::PatternSetSpec patterns = pile.capture.metadata.pattern_set;
  double seconds[2];
  for (const auto* photometry : {&one_ray, &mixed}) {
    const core::Stopwatch images;
    simulation::renderPileImages(part.mesh, pile.scene, pile.params, patterns, *photometry);
    seconds[photometry == &mixed] = images.elapsedMs() / 1000.0;
  }
  std::printf("  images alone: %.2f s with one ray per pixel, %.2f s with %dx%d rays at edge pixels\n", seconds[0],
              seconds[1], mixed.mixed_pixel_samples, mixed.mixed_pixel_samples);
}

void benchReconstruction(const Options& o) {
  const simulation::Part part = simulation::makePart(o.part);
  std::vector<io::RigCalibration> rigs{simulation::makeVirtualRig()};
  if (!o.skip_large) rigs.push_back(largeRig());
  std::vector<SpeedResult> speed;
  std::vector<Accuracy> accuracy;
  for (const io::RigCalibration& rig : rigs) {
    const core::Stopwatch render;
    const RenderedPile pile = renderPile(part, rig, 1, o, defaultPatterns(rig));
    std::printf("rendered %dx%d: %zu images of %s x %d in %.1f s\n", rig.camera.width, rig.camera.height,
                pile.capture.images.size(), o.part.c_str(), kObjects, render.elapsedMs() / 1000.0);
    printMixedPixelCost(part, pile, o);
    std::fflush(stdout);
    reconstruction::Reconstruction result;
    speed.push_back(measureSpeed(rig, pile.capture, o, result));
    accuracy.push_back(measureAccuracy(speed.back().name, pile, result));
    // The same capture without the depth-edge filter (both its tests): what it removes.
    reconstruction::ReconstructionParams edges_kept = reconstructionParams(o);
    if (edges_kept.filter.edge_max_jump == 0.0 && edges_kept.filter.edge_side_reach == 0) continue;
    edges_kept.filter.edge_max_jump = 0.0;
    edges_kept.filter.edge_side_reach = 0;
    accuracy.push_back(measureAccuracy(speed.back().name + " edge filter off", pile,
                                       reconstruction::Reconstructor(rig, edges_kept).reconstruct(pile.capture)));
  }
  printSpeed(speed, o);
  printAccuracy(accuracy, o.part, o.lighting);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options options = parse(argc, argv);
    const simulation::PhotometryParams photometry = photometryFor(options);
    std::printf(
        "bench_reconstruction: %d threads (--threads %d), default pattern set (Gray columns + "
        "rows, 4 phase steps), %s lighting, mixed pixels %dx%d rays with %.2f px camera blur, reconstruction "
        "settings: %s\n",
        core::resolveThreadCount(options.threads), options.threads, options.lighting.c_str(),
        photometry.mixed_pixel_samples, photometry.mixed_pixel_samples, photometry.camera_blur_sigma,
        options.settings.empty() ? "defaults" : options.settings.c_str());
    if (options.pattern_sets) {
      benchPatternSets(options);
      return 0;
    }
    benchReconstruction(options);
    if (!options.skip_detection) benchDetection(options);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
}
