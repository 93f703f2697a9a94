#pragma once
// Reconstruction settings from the `reconstruction:` section of a cell's YAML settings file
// (config/reconstruction.yaml lists every key with its default and unit). Every key is optional;
// an unknown key, a wrong type or an invalid value throws core::Error naming the file and the
// key. The other sections of the file (model, detection) belong to estimation and are not read
// here. Thread-safe (no shared state).
#include <string>

#include "binpick/core/yaml_section.hpp"
#include "binpick/reconstruction/reconstruction.hpp"

namespace binpick::reconstruction {

ReconstructionParams loadReconstructionParams(const std::string& path);
// The same from YAML text; `origin` names it in error messages.
ReconstructionParams parseReconstructionParams(const std::string& yaml_text, const std::string& origin);
// The `reconstruction:` section of a larger settings file (e.g. the daemon's), validated.
ReconstructionParams readReconstructionSection(core::YamlSection section, const std::string& origin);

}  // namespace binpick::reconstruction
