// YamlSection: typed reads with typo detection.
#include "binpick/core/yaml_section.hpp"

#include <vector>

#include "binpick/core/file.hpp"

namespace binpick::core {

YamlSection::YamlSection(const YAML::Node& node, std::string path, const std::string& origin)
    : node_(node), path_(std::move(path)), origin_(origin) {
  if (node_ && !node_.IsNull() && !node_.IsMap()) throw Error(origin_ + ": " + path_ + " must be a mapping");
}

void YamlSection::readVector3(const char* key, Eigen::Vector3d& value) {
  if (!has(key)) {
    used_.insert(key);
    return;
  }
  std::vector<double> values;
  read(key, values);
  if (values.size() != 3) fail(key, "needs three numbers");
  value = Eigen::Vector3d(values[0], values[1], values[2]);
}

YamlSection YamlSection::child(const char* key) {
  used_.insert(key);
  return YamlSection(node_ ? node_[key] : YAML::Node(), path_ + key + ".", origin_);
}

void YamlSection::finish() const {
  if (!node_ || !node_.IsMap()) return;
  for (const auto& entry : node_) {
    // A key may be any node in YAML (`[a, b]: 1`, `? {x: 1}`); none of ours is anything but text.
    if (!entry.first.IsScalar()) {
      const std::string where = path_.empty() ? "the top level" : path_.substr(0, path_.size() - 1);
      throw Error(origin_ + ": " + where + " has a key that is not a name (a list, a mapping or empty)");
    }
    const std::string key = entry.first.Scalar();
    if (!used_.count(key)) fail(key, "is not a known setting");
  }
}

void YamlSection::fail(const std::string& key, const std::string& why) const {
  throw Error(origin_ + ": " + path_ + key + " " + why);
}

YAML::Node parseYaml(const std::string& text, const std::string& origin) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw Error(origin + ": not valid YAML (line " + std::to_string(e.mark.line + 1) + "): " + e.msg);
  }
}

std::string readConfigFile(const std::string& path) {
  // Read as one regular file of known size, never streamed to its end: a settings file naming
  // /dev/zero or a FIFO as a grasps or hand-eye file must be refused, not read forever.
  try {
    return readFile(path);
  } catch (const Error& e) {
    std::string reason = e.what();
    if (reason.compare(0, path.size() + 2, path + ": ") == 0) reason.erase(0, path.size() + 2);
    throw Error(path + ": cannot open the configuration file (" + reason + ")");
  }
}

}  // namespace binpick::core
