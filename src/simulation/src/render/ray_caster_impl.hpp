#pragma once
// What a RayCaster holds: copies of the meshes, the placed objects, and the Embree scenes built
// from them. Internal to binpick::simulation; immutable once built.
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <vector>

#include "binpick/io/point_cloud.hpp"
#include "binpick/simulation/ray_caster.hpp"
#include "embree_device.hpp"

namespace binpick::simulation {

namespace detail {

struct PlacedObject {
  int mesh = -1;  // index into RayCaster::Impl::meshes; -1 for an empty mesh (never hit)
  Eigen::Isometry3d T_camera_object = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_object_camera = Eigen::Isometry3d::Identity();
  int32_t id = 0;
  Eigen::AlignedBox3d bounds;  // camera frame; empty for an empty mesh
};

// Everything a RayCaster holds.
struct CasterScene {
  // One copy per distinct mesh: a part placed twenty times is stored once.
  std::vector<io::TriangleMesh> meshes;
  std::vector<PlacedObject> objects;
  // Declared before the scenes, so destroyed after them.
  std::unique_ptr<EmbreeDevice> device;
  // Every object, with Embree geometry ID = object index.
  SceneHandle scene;
  // One scene per object holding just that object (geometry ID 0), sharing its geometry.
  std::vector<SceneHandle> alone_scenes;
};

// Builds everything from the objects (validation, baking into the camera frame, BVH builds).
CasterScene buildCasterScene(const std::vector<RenderObject>& objects);

}  // namespace detail

struct RayCaster::Impl {
  detail::CasterScene data;

  void requireIndex(int object_index, const char* caller) const;
};

}  // namespace binpick::simulation
