#pragma once
// Reading settings files: one YAML mapping at a time, remembering which keys were read so that a
// typo is reported instead of silently ignored. Errors are "ORIGIN: path.to.key what was wrong".
// A Section is used by one thread at a time.
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <set>
#include <string>

#include "binpick/core/error.hpp"

namespace binpick::core {

class YamlSection {
 public:
  // `node` may be undefined or null (an absent section: every read keeps its default).
  YamlSection(const YAML::Node& node, std::string path, const std::string& origin);

  // Sets `value` from `key` when present; throws when it has the wrong type.
  template <class T>
  void read(const char* key, T& value) {
    used_.insert(key);
    if (!node_ || !node_[key]) return;
    try {
      value = node_[key].as<T>();
    } catch (const YAML::Exception&) {
      fail(key, "has the wrong type");
    }
  }
  // Three numbers, e.g. [x, y, z]; throws when present with another count.
  void readVector3(const char* key, Eigen::Vector3d& value);
  YamlSection child(const char* key);
  // A key that another reader of the same file handles: known, not read here.
  void skip(const char* key) { used_.insert(key); }
  bool has(const char* key) const { return node_ && node_[key]; }
  bool isNull() const { return !node_ || node_.IsNull(); }
  const YAML::Node& node() const { return node_; }

  // Throws on a key of the mapping that was neither read nor skipped.
  void finish() const;
  [[noreturn]] void fail(const std::string& key, const std::string& why) const;

 private:
  YAML::Node node_;
  std::string path_;
  std::string origin_;  // a copy: callers pass temporaries ("binpickd.yaml"), gone before a later fail()
  std::set<std::string> used_;
};

// Runs `check` (validate() of the params a file set), prefixing its error with "ORIGIN: " so
// that the message names the file as well as the field.
template <typename Check>
void validateSettings(const std::string& origin, const Check& check) {
  try {
    check();
  } catch (const Error& e) {
    throw Error(origin + ": " + e.what());
  }
}

// Parses YAML text; throws "ORIGIN: not valid YAML (line N): ..." on a syntax error.
YAML::Node parseYaml(const std::string& text, const std::string& origin);
// The text of a settings file (a regular file); throws "PATH: cannot open the configuration file
// (REASON)".
std::string readConfigFile(const std::string& path);

}  // namespace binpick::core
