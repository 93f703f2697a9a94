// buildCasterScene: checks the objects, bakes each placed mesh into the camera frame and builds
// the Embree scenes.
#include <map>
#include <string>

#include "binpick/core/error.hpp"
#include "ray_caster_impl.hpp"

namespace binpick::simulation::detail {
namespace {

std::string describe(std::size_t index, const RenderObject& object) {
  return "RayCaster: object " + std::to_string(index) + " (id " + std::to_string(object.id) + ")";
}

// Normals and object-frame points are carried through the pose as a rotation, so it must be one.
void requireRigidPose(const Eigen::Isometry3d& pose, const std::string& what) {
  if (!pose.matrix().allFinite()) throw core::Error(what + ": the pose has non-finite entries");
  const Eigen::Matrix3d r = pose.linear();
  const double orthonormality = (r.transpose() * r - Eigen::Matrix3d::Identity()).norm();
  if (orthonormality > 1e-6 || r.determinant() < 0.0) {
    throw core::Error(what + ": the pose is not a rigid transform (rotation + translation)");
  }
}

// Float camera-frame vertices cost ~1e-7 m at a metre; hits are refined in double afterwards.
GeometryHandle bakeGeometry(const EmbreeDevice& device, const io::TriangleMesh& mesh,
                            const Eigen::Isometry3d& T_camera_object, const std::string& what) {
  GeometryHandle geometry(rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE));
  device.throwIfFailed(what);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry.get(), RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertices.size()));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry.get(), RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangles.size()));
  device.throwIfFailed(what);
  if (vertices == nullptr || indices == nullptr) throw core::Error(what + ": Embree returned no buffer");
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3f p = (T_camera_object * mesh.vertices[i].cast<double>()).cast<float>();
    for (int k = 0; k < 3; ++k) vertices[3 * i + k] = p[k];
  }
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) indices[3 * i + k] = static_cast<unsigned>(mesh.triangles[i][k]);
  }
  rtcCommitGeometry(geometry.get());
  device.throwIfFailed(what);
  return geometry;
}

Eigen::AlignedBox3d placedBounds(const io::TriangleMesh& mesh, const Eigen::Isometry3d& pose) {
  Eigen::AlignedBox3d box;
  for (const auto& v : mesh.vertices) box.extend(pose * v.cast<double>());
  return box;
}

// Copies the meshes (once each) and records where every object is.
void placeObjects(const std::vector<RenderObject>& objects, CasterScene& built) {
  std::map<const io::TriangleMesh*, int> mesh_index;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const RenderObject& object = objects[i];
    const std::string what = describe(i, object);
    if (object.mesh == nullptr) throw core::Error(what + ": the mesh pointer is null");
    requireRigidPose(object.T_camera_object, what);
    PlacedObject placed;
    placed.T_camera_object = object.T_camera_object;
    placed.T_object_camera = object.T_camera_object.inverse(Eigen::Isometry);
    placed.id = object.id;
    if (!object.mesh->empty()) {
      auto [it, inserted] = mesh_index.emplace(object.mesh, static_cast<int>(built.meshes.size()));
      if (inserted) {
        io::validateMesh(*object.mesh, what + " mesh");
        built.meshes.push_back(*object.mesh);
      }
      placed.mesh = it->second;
      placed.bounds = placedBounds(*object.mesh, object.T_camera_object);
    }
    built.objects.push_back(placed);
  }
}

// The whole scene and one scene per object, sharing each object's baked geometry.
void buildScenes(const std::vector<RenderObject>& objects, CasterScene& built) {
  built.device = std::make_unique<EmbreeDevice>();
  built.scene = newScene(*built.device);
  for (std::size_t i = 0; i < objects.size(); ++i) {
    built.alone_scenes.push_back(newScene(*built.device));
    const PlacedObject& placed = built.objects[i];
    if (placed.mesh >= 0) {
      const std::string what = describe(i, objects[i]);
      const GeometryHandle geometry =
          bakeGeometry(*built.device, built.meshes[placed.mesh], placed.T_camera_object, what);
      // The scenes keep their own references to the geometry.
      rtcAttachGeometryByID(built.scene.get(), geometry.get(), static_cast<unsigned>(i));
      rtcAttachGeometryByID(built.alone_scenes.back().get(), geometry.get(), 0);
      built.device->throwIfFailed(what);
    }
    rtcCommitScene(built.alone_scenes.back().get());
    built.device->throwIfFailed(describe(i, objects[i]) + ": building its scene");
  }
  rtcCommitScene(built.scene.get());
  built.device->throwIfFailed("RayCaster: building the scene");
}

}  // namespace

CasterScene buildCasterScene(const std::vector<RenderObject>& objects) {
  CasterScene built;
  placeObjects(objects, built);
  buildScenes(objects, built);
  return built;
}

}  // namespace binpick::simulation::detail
