#include "binpick/cell/grasps_file.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "binpick/core/file.hpp"
#include "binpick/core/pose_yaml.hpp"
#include "binpick/core/yaml_section.hpp"

namespace binpick::cell {
namespace {

std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

}  // namespace

std::vector<picking::Grasp> readGraspList(const YAML::Node& list, const std::string& path, const std::string& origin) {
  if (!list || !list.IsSequence() || list.size() == 0) {
    throw core::Error(origin + ": " + path + "grasps needs a list of at least one grasp");
  }
  std::vector<picking::Grasp> grasps;
  for (std::size_t i = 0; i < list.size(); ++i) {
    core::YamlSection entry(list[i], path + "grasps[" + std::to_string(i) + "].", origin);
    picking::Grasp grasp;
    grasp.name = "grasp " + std::to_string(i);
    entry.read("name", grasp.name);
    entry.read("quality", grasp.quality);
    if (!(grasp.quality >= 0.0 && grasp.quality <= 1.0)) entry.fail("quality", "must be in [0, 1]");
    entry.read("width", grasp.width);
    if (!(grasp.width >= 0.0 && std::isfinite(grasp.width))) entry.fail("width", "must be >= 0 (metres)");
    grasp.T_model_grasp = core::readPose(entry);  // also rejects unknown keys
    grasps.push_back(grasp);
  }
  return grasps;
}

std::vector<picking::Grasp> readGraspsFile(const std::string& path) {
  core::YamlSection top(core::parseYaml(core::readConfigFile(path), path), "", path);
  if (top.isNull()) throw core::Error(path + ": the grasps file is empty");
  top.skip("grasps");
  top.finish();
  return readGraspList(top.node()["grasps"], "", path);
}

std::string graspsYaml(const std::vector<picking::Grasp>& grasps, const std::string& comment) {
  std::ostringstream text;
  std::istringstream comment_lines(comment);
  for (std::string line; std::getline(comment_lines, line);) text << "# " << line << "\n";
  text << "grasps:\n";
  for (const picking::Grasp& grasp : grasps) {
    text << "  - name: " << quoted(grasp.name) << "\n"
         << core::poseYaml(grasp.T_model_grasp, "    ") << "    quality: " << core::yamlNumber(grasp.quality) << "\n";
    // parallel jaws: metres between the contacts
    if (grasp.width > 0.0) text << "    width: " << core::yamlNumber(grasp.width) << "\n";
  }
  return text.str();
}

void writeGraspsFile(const std::string& path, const std::vector<picking::Grasp>& grasps, const std::string& comment) {
  core::writeFileAtomically(path, graspsYaml(grasps, comment));
}

}  // namespace binpick::cell
