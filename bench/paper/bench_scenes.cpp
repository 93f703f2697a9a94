#include "bench_scenes.hpp"

#include "binpick/core/error.hpp"
#include "binpick/core/stopwatch.hpp"
#include "binpick/evaluation/evaluation.hpp"
#include "binpick/reconstruction/reconstruction.hpp"
#include "pose_method.hpp"

namespace binpick::bench {
namespace {

void setPileParams(const SceneRequest& request, simulation::PileParams& p) {
  p.objects = request.objects;
  p.seed = request.seed;
  p.rig = request.rig;
  p.threads = request.threads;
  p.depth_noise = 0.0;  // the exact input; the reconstructed one gets its noise from the images
}

// The default pattern set (Gray code columns + rows, phase shift) at the projector's size.
io::PatternSetSpec patternsFor(const io::RigCalibration& rig) {
  io::PatternSetSpec patterns;
  patterns.projector_width = rig.projector.width;
  patterns.projector_height = rig.projector.height;
  return patterns;
}

}  // namespace

std::string inputName(CloudInput input) { return input == CloudInput::Exact ? "exact" : "reconstructed"; }

const io::PointCloud& BenchScene::cloud(CloudInput input) const {
  if (input == CloudInput::Exact) return truth.cloud;
  if (reconstructed.empty()) throw core::Error("bench: the scene was made without its reconstructed cloud");
  return reconstructed;
}

std::size_t BenchScene::pointsInBin(CloudInput input) const {
  return input == CloudInput::Exact ? exact_in_bin : reconstructed_in_bin;
}

BenchScene makeBenchScene(const simulation::Part& part, const SceneRequest& request) {
  BenchScene s;
  setPileParams(request, s.params);
  if (!request.reconstruct) {
    s.truth = simulation::generatePile(part.mesh, s.params);
  } else {
    const io::PatternSetSpec patterns = patternsFor(request.rig);
    simulation::PhotometryParams photometry;
    photometry.seed = request.seed;
    simulation::PileCapture pile = simulation::generatePileCapture(part.mesh, s.params, patterns, photometry);
    s.truth = std::move(pile.scene);
    const io::Capture capture =
        simulation::recordedCapture(std::move(pile.images), s.params, patterns, photometry, "bench_paper " + part.name);
    reconstruction::ReconstructionParams params = request.reconstruction;
    params.setThreads(request.threads);
    const reconstruction::Reconstructor reconstructor(request.rig, params);
    const core::Stopwatch stopwatch;
    s.reconstructed = reconstructor.reconstruct(capture).cloud;
    s.reconstruct_ms = stopwatch.elapsedMs();
  }
  s.crop = evaluation::binInterior(s.truth, s.params);
  s.exact_in_bin = croppedPoints({&s.truth.cloud, s.crop}).size();
  s.reconstructed_in_bin = croppedPoints({&s.reconstructed, s.crop}).size();
  return s;
}

}  // namespace binpick::bench
