#pragma once
// The benchmark's scenes: a virtual-cell pile with its ground truth, seen two ways, and the same
// for every method. "exact" is the structured-light cloud without noise (the pixels the camera
// sees lit by the projector, exact depth); "reconstructed" is the cloud decoded and triangulated
// from the rendered pattern images (the whole pipeline).
#include <cstdint>
#include <string>

#include "scene.hpp"
#include "binpick/io/point_cloud.hpp"
#include "binpick/reconstruction/reconstruction.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/pile.hpp"

namespace binpick::bench {

enum class CloudInput { Exact, Reconstructed };
std::string inputName(CloudInput input);  // "exact" | "reconstructed"

struct SceneRequest {
  int objects = 20;
  uint64_t seed = 1;
  bool reconstruct = true;  // also render the patterns and reconstruct
  io::RigCalibration rig = simulation::makeVirtualRig();
  int threads = 0;                                      // rendering and reconstruction; 0: all
  reconstruction::ReconstructionParams reconstruction;  // its threads are set from `threads`
};

struct BenchScene {
  simulation::PileParams params;
  simulation::PileScene truth;                             // truth.cloud is the exact input
  io::PointCloud reconstructed;                            // empty unless requested
  estimation::CropBox crop;                                // the bin's inside
  double reconstruct_ms = 0.0;                             // decode + triangulate + filter, from images in memory
  std::size_t exact_in_bin = 0, reconstructed_in_bin = 0;  // finite points inside the crop
  const io::PointCloud& cloud(CloudInput input) const;
  std::size_t pointsInBin(CloudInput input) const;
};

BenchScene makeBenchScene(const simulation::Part& part, const SceneRequest& request);

}  // namespace binpick::bench
