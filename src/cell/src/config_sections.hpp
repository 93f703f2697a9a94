#pragma once
// Readers of binpickd's settings sections (cell_config.cpp puts them together).
#include <string>
#include <vector>

#include "binpick/cell/cell_config.hpp"
#include "binpick/core/yaml_section.hpp"

namespace binpick::cell {

// Paths in the file are relative to its directory.
struct PathResolver {
  std::string base_directory;
  std::string operator()(const std::string& path) const;
};

SourceConfig readSource(core::YamlSection section, const PathResolver& resolve);
std::vector<RecipeConfig> readRecipes(const YAML::Node& list, const std::string& origin, const PathResolver& resolve);
picking::PickParams readPicking(core::YamlSection section);
robot::RobotServerParams readRobot(core::YamlSection section);
CycleLimits readLimits(core::YamlSection section);
std::optional<ArtefactParams> readArtefacts(core::YamlSection section, const PathResolver& resolve);
std::optional<WebViewConfig> readWebView(core::YamlSection section);

}  // namespace binpick::cell
