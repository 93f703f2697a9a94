#pragma once
// Small helpers shared by the benchmark executables.
#include <Eigen/Geometry>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "binpick/io/geometry_io.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/pile.hpp"

namespace binpick::bench {

// "a,b,,c" -> {"a", "b", "c"}: the value of a list option such as --parts.
inline std::vector<std::string> splitCommas(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

// A user's mesh as a part: FILE or FILE:SCALE (an STL in millimetres: FILE:0.001); its symmetry
// found from the mesh (printed).
inline simulation::Part meshPart(const std::string& spec) {
  const auto colon = spec.rfind(':');
  const bool scaled = colon != std::string::npos && colon > 0;
  const std::string file = scaled ? spec.substr(0, colon) : spec;
  io::TriangleMesh mesh = io::readMesh(file);
  const float scale = scaled ? std::stof(spec.substr(colon + 1)) : 1.0f;
  for (auto& v : mesh.vertices) v *= scale;
  simulation::Part part = simulation::partFromMesh(std::filesystem::path(file).stem().string(), std::move(mesh));
  std::fprintf(stderr, "%s: %s\n", part.name.c_str(), part.description.c_str());
  return part;
}

// The part whose pose lies nearest a detected one (by the distance of their origins) and the
// error against it, symmetry folded: what a wrong detection was near.
struct Nearest {
  int object = -1;
  simulation::PoseError error{1e9, 0.0};
};

inline Nearest nearestObject(const Eigen::Isometry3f& pose, const std::vector<simulation::ObjectTruth>& objects,
                             const simulation::Symmetry& symmetry) {
  Nearest nearest;
  for (std::size_t j = 0; j < objects.size(); ++j) {
    const auto e = simulation::poseError(pose.cast<double>(), objects[j].T_camera_object, symmetry);
    if (e.translation < nearest.error.translation) nearest = {static_cast<int>(j), e};
  }
  return nearest;
}

}  // namespace binpick::bench
