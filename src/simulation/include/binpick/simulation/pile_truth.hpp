#pragma once
// The ground truth of a simulated pile on disk: DIR/truth/ of a capture directory
// (docs/capture-format.md): objects.json, depth.tiff, mask.png, cloud.ply, part.ply.
// Stateless functions: thread-safe for different directories.
#include <string>
#include <vector>

#include "binpick/simulation/pile.hpp"

namespace binpick::simulation {

struct PileTruth {
  std::string part;  // built-in part name, or the mesh file the pile was made of
  Eigen::Isometry3d T_camera_bin = Eigen::Isometry3d::Identity();
  std::vector<ObjectTruth> objects;
};

// Writes DIR/truth/ (creating it). Throws core::Error naming the file that cannot be written.
void writePileTruth(const std::string& capture_directory, const PileScene& scene, const std::string& part_name,
                    const io::TriangleMesh& part);

// Reads DIR/truth/objects.json (or the file itself when given one). Throws core::Error
// "PATH: ..." on a missing file, malformed JSON or a bad pose.
PileTruth readPileTruth(const std::string& path);

}  // namespace binpick::simulation
