// Camera + projector calibration benchmark on the virtual cell, whose rig is known:
// 1. a full-resolution calibration sequence (the virtual rig, the full pattern set) rendered and
//    measured view by view: camera and projector corners against the true pixels, time per stage;
// 2. the calibration: reprojection RMS, the recovered intrinsics and extrinsics against the true
//    rig, with the intrinsics refined in the stereo step (the default) and held fixed;
// 3. depth: a pile of parts rendered with the true rig and reconstructed with the true and with
//    the recovered calibration, compared with each other and with the rendered depth.
//
// With --projector-k3 the true projector lens gets that sixth-order term; --projector-distortion
// chooses the terms its fit may change; --max-offset widens the spread of board poses (the board
// centre's direction off the camera axis, normalised). The projector's lens is then compared with
// the truth over its image, at the corners in particular.
//
//   bench_calibration_rig [--poses 12] [--board charuco|chessboard] [--seed 1] [--objects 10]
//                         [--projector-k3 K] [--projector-distortion TERMS] [--max-offset 0.2]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "binpick/calibration/rig_calibrator.hpp"
#include "binpick/core/error.hpp"
#include "binpick/core/stopwatch.hpp"
#include "binpick/reconstruction/pattern_set.hpp"
#include "binpick/reconstruction/reconstruction.hpp"
#include "binpick/simulation/calibration_sequence.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/pile.hpp"

namespace {

using namespace binpick;
constexpr double kDegree = 3.14159265358979323846 / 180.0;

struct Options {
  int poses = 12;
  std::string board = "charuco";
  int seed = 1;
  int objects = 10;
  double projector_k3 = 0.0;
  std::string projector_distortion = "k1,k2,p1,p2";
  double max_offset = 0.2;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (i + 1 >= argc) throw core::Error("bench_calibration_rig: " + flag + " needs a value");
    const std::string value = argv[++i];
    if (flag == "--poses")
      o.poses = std::stoi(value);
    else if (flag == "--board")
      o.board = value;
    else if (flag == "--seed")
      o.seed = std::stoi(value);
    else if (flag == "--objects")
      o.objects = std::stoi(value);
    else if (flag == "--projector-k3")
      o.projector_k3 = std::stod(value);
    else if (flag == "--projector-distortion")
      o.projector_distortion = value;
    else if (flag == "--max-offset")
      o.max_offset = std::stod(value);
    else
      throw core::Error("bench_calibration_rig: unknown option " + flag);
  }
  if (o.poses < 3 || o.objects < 0)
    throw core::Error("bench_calibration_rig: --poses >= 3, --objects >= 0 (0: no depth)");
  return o;
}

double quantile(std::vector<double> values, double q) {
  if (values.empty()) return NAN;
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(q * static_cast<double>(values.size() - 1) + 0.5)];
}

void printQuantiles(const char* label, const std::vector<double>& values, const char* unit) {
  std::printf("  %-44s median %.3f  p95 %.3f  max %.3f %s (%zu)\n", label, quantile(values, 0.5),
              quantile(values, 0.95), quantile(values, 1.0), unit, values.size());
}

// ---------------------------------------------------------------------------------------------
// 1. The sequence, rendered and measured one view at a time (a full-resolution view under the
//    full pattern set is 68 MB of images).

struct MeasuredSequence {
  std::vector<calibration::RigView> views;
  std::vector<double> camera_errors_px, projector_errors_px;
  double render_ms = 0.0;
  calibration::RigViewTimings timings;  // summed over the views
};

void compareWithTruth(const calibration::RigView& view, const std::vector<simulation::CornerObservation>& truth,
                      MeasuredSequence& m) {
  std::map<int, simulation::CornerObservation> by_id;
  for (const simulation::CornerObservation& corner : truth) by_id[corner.id] = corner;
  for (std::size_t i = 0; i < view.board.ids.size(); ++i) {
    m.camera_errors_px.push_back((view.board.pixels[i] - by_id.at(view.board.ids[i]).camera_pixel).norm());
  }
  for (const calibration::ProjectorCorner& corner : view.projector.corners) {
    m.projector_errors_px.push_back((corner.projector - by_id.at(corner.id).projector_pixel).norm());
  }
}

MeasuredSequence measureSequence(const simulation::CalibrationSequenceParams& params,
                                 const calibration::BoardLayout& layout) {
  const simulation::CalibrationBoard board(params.board, params.texel_size);
  const std::vector<Eigen::Isometry3d> poses = simulation::randomBoardPoses(board, params.rig, params.poses);
  MeasuredSequence m;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const core::Stopwatch render;
    const io::Capture capture = simulation::renderCalibrationCapture(board, poses[i], params, 100 + i);
    m.render_ms += render.elapsedMs();
    char name[32];
    std::snprintf(name, sizeof name, "pose_%03zu", i);
    m.views.push_back(calibration::measureRigView(capture, name, layout));
    const calibration::RigView& view = m.views.back();
    m.timings.decode += view.timings.decode;
    m.timings.detect += view.timings.detect;
    m.timings.projector_corners += view.timings.projector_corners;
    compareWithTruth(view, simulation::observeCorners(board, params.rig, poses[i]), m);
    std::printf("  %s: %zu of %d corners, %zu with a projector pixel\n", name, view.board.ids.size(),
                view.board.expected, view.projector.corners.size());
    std::fflush(stdout);
  }
  return m;
}

// How far out the projector corners reach: the largest distance from the principal point, as a
// share of the distance to the image corner (the radial terms are measured only where corners are).
void printProjectorCoverage(const MeasuredSequence& m, const io::LensIntrinsics& projector) {
  const Eigen::Vector2d centre(projector.cx, projector.cy);
  const double half_diagonal = Eigen::Vector2d(std::max(projector.cx, projector.width - 1 - projector.cx),
                                               std::max(projector.cy, projector.height - 1 - projector.cy))
                                   .norm();
  std::vector<double> reach;
  for (const calibration::RigView& view : m.views) {
    for (const calibration::ProjectorCorner& corner : view.projector.corners) {
      reach.push_back((corner.projector - centre).norm() / half_diagonal);
    }
  }
  std::printf("  projector corners reach %.0f %% of the half-diagonal (95th percentile %.0f %%)\n",
              100.0 * quantile(reach, 1.0), 100.0 * quantile(reach, 0.95));
}

void printSequence(const MeasuredSequence& m) {
  const double n = static_cast<double>(m.views.size());
  printQuantiles("camera corners vs truth", m.camera_errors_px, "px");
  printQuantiles("projector corners vs truth", m.projector_errors_px, "px");
  std::printf("  time per view: render %.0f ms (setup); decode %.0f, detect %.0f, projector corners %.0f ms\n",
              m.render_ms / n, m.timings.decode / n, m.timings.detect / n, m.timings.projector_corners / n);
}

// ---------------------------------------------------------------------------------------------
// 2. The calibration against the true rig.

void printLensErrors(const char* device, const io::LensIntrinsics& lens, const io::LensIntrinsics& truth) {
  std::printf("  %-9s fx %+.2f  fy %+.2f  cx %+.2f  cy %+.2f px (of fx %.0f)\n", device, lens.fx - truth.fx,
              lens.fy - truth.fy, lens.cx - truth.cx, lens.cy - truth.cy, truth.fx);
}

void printLensFit(const char* device, const calibration::LensFitReport& fit) {
  std::printf("  %-9s terms %s, own solve RMS %.4f px; per term RMS fitted / held:\n", device, fit.terms.text().c_str(),
              fit.rms_px);
  for (int term = 0; term < calibration::kDistortionTermCount; ++term) {
    const calibration::TermResidual& r = fit.per_term[static_cast<std::size_t>(term)];
    std::printf("    %-5s %-6s %.4f / %.4f px  value %+.5f +- %.5f\n", calibration::kDistortionTermNames[term],
                r.chosen ? "chosen" : "", r.rms_fitted_px, r.rms_held_px, r.value[0], r.sd[0]);
  }
}

// How far the recovered lens puts each pixel's true ray from that pixel: at the image corners and
// over a grid of the whole image.
void printLensModelError(const char* device, const io::LensIntrinsics& lens, const io::LensIntrinsics& truth) {
  std::vector<double> grid, corners;
  const int steps = 32;
  for (int j = 0; j <= steps; ++j) {
    for (int i = 0; i <= steps; ++i) {
      const Eigen::Vector2d pixel((truth.width - 1) * i / double(steps), (truth.height - 1) * j / double(steps));
      const double error = (lens.project(truth.rayThroughPixel(pixel)) - pixel).norm();
      grid.push_back(error);
      if ((i == 0 || i == steps) && (j == 0 || j == steps)) corners.push_back(error);
    }
  }
  std::printf("  %-9s lens vs truth: image corners %.3f %.3f %.3f %.3f px; whole image median %.3f max %.3f px\n",
              device, corners[0], corners[1], corners[2], corners[3], quantile(grid, 0.5), quantile(grid, 1.0));
}

void printCalibration(const char* label, const calibration::RigCalibrationResult& r, const io::RigCalibration& truth) {
  const Eigen::Isometry3d& T = r.rig.T_projector_camera;
  const Eigen::Isometry3d& T_true = truth.T_projector_camera;
  const double rotation = Eigen::AngleAxisd(T.linear().transpose() * T_true.linear()).angle();
  std::printf("%s\n", label);
  std::printf("  RMS camera %.3f px, projector %.3f px, stereo %.3f px; %d of %zu views used\n",
              r.quality.camera_rms_px, r.quality.projector_rms_px, r.quality.stereo_rms_px, r.quality.viewsUsed(),
              r.quality.views.size());
  printLensErrors("camera", r.rig.camera, truth.camera);
  printLensErrors("projector", r.rig.projector, truth.projector);
  printLensFit("camera", r.camera_fit);
  printLensFit("projector", r.projector_fit);
  printLensModelError("camera", r.rig.camera, truth.camera);
  printLensModelError("projector", r.rig.projector, truth.projector);
  std::printf("  baseline %+.3f mm (|T| %.2f mm), T off by %.3f mm, rotation off by %.4f deg\n",
              1e3 * (T.translation().norm() - T_true.translation().norm()), 1e3 * T_true.translation().norm(),
              1e3 * (T.translation() - T_true.translation()).norm(), rotation / kDegree);
  std::printf("  time: camera %.0f ms, projector %.0f ms, stereo %.0f ms\n", r.timings.camera, r.timings.projector,
              r.timings.stereo);
  for (const std::string& warning : r.warnings) std::printf("  warning: %s\n", warning.c_str());
}

// ---------------------------------------------------------------------------------------------
// 3. Depth of a pile reconstructed with the true and with the recovered calibration.

struct DepthErrors {
  std::vector<double> between, true_vs_depth, recovered_vs_depth;  // |dz|, mm
};

DepthErrors compareDepth(const simulation::PileScene& scene, const io::PointCloud& with_true,
                         const io::PointCloud& with_recovered) {
  DepthErrors e;
  for (std::size_t i = 0; i < with_true.points.size(); ++i) {
    const Eigen::Vector3f a = with_true.points[i], b = with_recovered.points[i];
    if (!a.allFinite() || !b.allFinite()) continue;
    e.between.push_back(1e3 * std::abs(static_cast<double>(a.z() - b.z())));
    if (!std::isfinite(scene.depth[i])) continue;
    e.true_vs_depth.push_back(1e3 * std::abs(static_cast<double>(a.z() - scene.depth[i])));
    e.recovered_vs_depth.push_back(1e3 * std::abs(static_cast<double>(b.z() - scene.depth[i])));
  }
  return e;
}

void benchDepth(const io::RigCalibration& truth, const io::RigCalibration& recovered, const Options& o) {
  simulation::PileParams params;
  params.objects = o.objects;
  params.seed = static_cast<uint64_t>(o.seed);
  params.rig = truth;
  io::PatternSetSpec patterns;
  patterns.projector_width = truth.projector.width;
  patterns.projector_height = truth.projector.height;
  simulation::PhotometryParams photometry;
  photometry.seed = params.seed;
  const simulation::Part part = simulation::makePart("l_bracket");
  simulation::PileCapture pile = simulation::generatePileCapture(part.mesh, params, patterns, photometry);
  const io::Capture capture =
      simulation::recordedCapture(std::move(pile.images), params, patterns, photometry, "bench_calibration_rig");
  const io::PointCloud with_true = reconstruction::Reconstructor(truth).reconstruct(capture).cloud;
  const io::PointCloud with_recovered = reconstruction::Reconstructor(recovered).reconstruct(capture).cloud;
  const DepthErrors e = compareDepth(pile.scene, with_true, with_recovered);
  std::printf("\n== 3. Depth of a pile (%d x l_bracket, seed %d), |dz| over pixels valid in both ==\n", o.objects,
              o.seed);
  printQuantiles("recovered vs true calibration", e.between, "mm");
  printQuantiles("true calibration vs rendered depth", e.true_vs_depth, "mm");
  printQuantiles("recovered calibration vs rendered depth", e.recovered_vs_depth, "mm");
  std::printf("  95th percentile: %.3f / %.3f / %.3f mm\n", quantile(e.between, 0.95), quantile(e.true_vs_depth, 0.95),
              quantile(e.recovered_vs_depth, 0.95));
}

void run(const Options& o) {
  simulation::CalibrationSequenceParams params;
  params.board.type = simulation::boardTypeFromName(o.board);
  params.poses.count = o.poses;
  params.poses.seed = static_cast<uint64_t>(o.seed);
  params.poses.max_offset = o.max_offset;
  params.rig.projector.distortion[4] = o.projector_k3;
  params.pattern_set.projector_width = params.rig.projector.width;
  params.pattern_set.projector_height = params.rig.projector.height;
  params.validate();
  const calibration::BoardLayout layout = params.board.layout();
  std::printf("projector k3 %.4f, fitted terms %s, pose offsets up to %.2f\n", o.projector_k3,
              o.projector_distortion.c_str(), o.max_offset);
  std::printf("bench_calibration_rig: %d %s poses, seed %d, camera %dx%d, projector %dx%d, %zu patterns\n", o.poses,
              o.board.c_str(), o.seed, params.rig.camera.width, params.rig.camera.height, params.rig.projector.width,
              params.rig.projector.height, reconstruction::patternNames(params.pattern_set).size());
  std::printf("\n== 1. Views (corners against the true pixels) ==\n");
  const MeasuredSequence m = measureSequence(params, layout);
  printSequence(m);
  printProjectorCoverage(m, params.rig.projector);

  std::printf("\n== 2. Calibration against the true rig ==\n");
  calibration::RigCalibrationParams refined_params;
  refined_params.projector_distortion =
      calibration::parseDistortionTerms(o.projector_distortion, "--projector-distortion");
  const calibration::RigCalibrationResult refined = calibration::calibrateRig(m.views, layout, refined_params);
  printCalibration("intrinsics refined in the stereo step (default)", refined, params.rig);
  calibration::RigCalibrationParams fixed_params = refined_params;
  fixed_params.refine_intrinsics_in_stereo = false;
  const calibration::RigCalibrationResult fixed = calibration::calibrateRig(m.views, layout, fixed_params);
  printCalibration("intrinsics held fixed in the stereo step", fixed, params.rig);

  if (o.objects > 0) benchDepth(params.rig, refined.rig, o);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    run(parse(argc, argv));
    return 0;
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
}
