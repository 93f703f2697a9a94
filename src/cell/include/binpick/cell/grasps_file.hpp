#pragma once
// Grasps as YAML: the file `binpick grasps` writes and a recipe's `grasps:` may name. The file
// holds one key, `grasps:`, a list of entries in the same form as a recipe's hand-written grasps:
//   {name: TEXT, translation: [x, y, z] (metres), rotation: [w, x, y, z], convention: quaternion,
//    quality: 0..1}
// (rotation in any robot orientation convention, robot_orientation.hpp; quality defaults to 1).
// Free functions without shared state: thread-safe.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "binpick/picking/picking.hpp"

namespace binpick::cell {

// The entries of a `grasps:` list; errors name "ORIGIN: PATHgrasps[i].key". Throws when the list
// is not a list of at least one grasp or a quality is outside [0, 1].
std::vector<picking::Grasp> readGraspList(const YAML::Node& list, const std::string& path, const std::string& origin);
// A grasps file; throws core::Error naming the file and key.
std::vector<picking::Grasp> readGraspsFile(const std::string& path);
// The file's text; `comment` (may hold several lines) is written first as YAML comments.
std::string graspsYaml(const std::vector<picking::Grasp>& grasps, const std::string& comment = "");
// Throws core::Error naming the file when it cannot be written.
void writeGraspsFile(const std::string& path, const std::vector<picking::Grasp>& grasps,
                     const std::string& comment = "");

}  // namespace binpick::cell
