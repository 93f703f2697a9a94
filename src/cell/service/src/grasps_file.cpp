#include "binpick/cell/grasps_file.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "binpick/io/yaml_section.hpp"
#include "config_pose.hpp"

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

std::vector<Grasp> readGraspList(const YAML::Node& list, const std::string& path, const std::string& origin) {
  if (!list || !list.IsSequence() || list.size() == 0) {
    throw Error(origin + ": " + path + "grasps needs a list of at least one grasp");
  }
  std::vector<Grasp> grasps;
  for (std::size_t i = 0; i < list.size(); ++i) {
    YamlSection entry(list[i], path + "grasps[" + std::to_string(i) + "].", origin);
    Grasp grasp;
    grasp.name = "grasp " + std::to_string(i);
    entry.read("name", grasp.name);
    entry.read("quality", grasp.quality);
    if (!(grasp.quality >= 0.0 && grasp.quality <= 1.0)) entry.fail("quality", "must be in [0, 1]");
    entry.read("width", grasp.width);
    if (!(grasp.width >= 0.0 && std::isfinite(grasp.width))) entry.fail("width", "must be >= 0 (metres)");
    grasp.T_model_grasp = readPose(entry);  // also rejects unknown keys
    grasps.push_back(grasp);
  }
  return grasps;
}

std::vector<Grasp> readGraspsFile(const std::string& path) {
  YamlSection top(parseYaml(readConfigFile(path), path), "", path);
  if (top.isNull()) throw Error(path + ": the grasps file is empty");
  top.skip("grasps");
  top.finish();
  return readGraspList(top.node()["grasps"], "", path);
}

std::string graspsYaml(const std::vector<Grasp>& grasps, const std::string& comment) {
  std::ostringstream text;
  std::istringstream comment_lines(comment);
  for (std::string line; std::getline(comment_lines, line);) text << "# " << line << "\n";
  text.precision(10);
  text << "grasps:\n";
  for (const Grasp& grasp : grasps) {
    Eigen::Quaterniond q(grasp.T_model_grasp.linear());
    if (q.w() < 0.0) q.coeffs() *= -1.0;  // w >= 0, as the robot conventions write it
    const Eigen::Vector3d t = grasp.T_model_grasp.translation();
    text << "  - name: " << quoted(grasp.name) << "\n"
         << "    translation: [" << t.x() << ", " << t.y() << ", " << t.z() << "]\n"
         << "    rotation: [" << q.w() << ", " << q.x() << ", " << q.y() << ", " << q.z() << "]\n"
         << "    convention: quaternion\n"
         << "    quality: " << grasp.quality << "\n";
    if (grasp.width > 0.0) text << "    width: " << grasp.width << "\n";  // parallel jaws: metres between the contacts
  }
  return text.str();
}

void writeGraspsFile(const std::string& path, const std::vector<Grasp>& grasps, const std::string& comment) {
  std::ofstream file(path);
  file << graspsYaml(grasps, comment);
  if (!file.good()) throw Error(path + ": cannot write the grasps file");
}

}  // namespace binpick::cell
