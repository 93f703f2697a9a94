#pragma once
// Ray queries against posed triangle meshes, for rendering what a camera and a projector see.
// Everything is in the camera frame (x right, y down, z forward, metres), as for renderDepth.
//
// A RayCaster copies the meshes and poses it is built from (the RenderObjects' meshes need not
// outlive it) and never changes afterwards: its queries are const and safe to call from any
// number of threads at once. Building it uses Embree's own thread pool.
//
// Hits are refined in double precision on the mesh's own triangle, so t, point, normal and
// object_point are exact to rounding for the mesh (float vertices) at its pose (Embree's float
// distance is kept only for rays within 1e-6 rad of a triangle's plane). They do not depend on
// how many threads query. One caveat: a ray through an edge shared by two triangles at exactly
// the same distance may report either triangle (which one follows the acceleration structure,
// whose build may differ between machines with different core counts); t, point and
// object_point agree either way, the triangle index and, on a crease, the normal may not.
#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "binpick/simulation/depth_renderer.hpp"

namespace binpick::simulation {

struct Ray {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();      // camera frame, metres
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  // normalised by the queries
  // The part of the ray searched, in metres along the normalised direction. A negative t_min
  // counts as 0: nothing behind the origin is ever reported.
  double t_min = 0.0;
  double t_max = std::numeric_limits<double>::infinity();
};

struct RayHit {
  double t = std::numeric_limits<double>::infinity();  // distance from the ray origin, metres
  Eigen::Vector3d point = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  // Unit geometric normal of the triangle hit, on the outside of the mesh as given by its
  // winding ((b - a) x (c - a)); camera frame. Not flipped towards the ray.
  Eigen::Vector3d normal = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  // The hit point in the frame of the object hit (its mesh coordinates).
  Eigen::Vector3d object_point = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  int32_t object_id = -1;  // RenderObject::id of the object hit; -1 when nothing was hit
  int object_index = -1;   // position of that object in the list given to the RayCaster, or -1
  int triangle = -1;       // index into the object's mesh triangles, or -1

  // Tells a hit from a miss even when an object's own id is -1.
  bool hit() const { return object_index >= 0; }
};

class RayCaster {
 public:
  // Throws core::Error naming the object when a mesh pointer is null, a mesh has non-finite
  // vertices or bad indices, or a pose is not a finite rigid transform; and when Embree fails
  // (no device on this CPU, out of memory), with Embree's message. Empty lists and empty meshes
  // are fine: they are never hit.
  explicit RayCaster(const std::vector<RenderObject>& objects);
  ~RayCaster();
  RayCaster(RayCaster&& other) noexcept;
  RayCaster& operator=(RayCaster&& other) noexcept;
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  int objectCount() const;
  // Throw core::Error on an index outside [0, objectCount()).
  int32_t objectId(int object_index) const;
  const Eigen::Isometry3d& objectPose(int object_index) const;  // T_camera_object
  // Axis-aligned bounds of the placed mesh in the camera frame; empty for an empty mesh.
  Eigen::AlignedBox3d objectBounds(int object_index) const;

  // The nearest surface along the ray within [t_min, t_max], or a miss (hit() false). A ray with
  // a non-finite or zero direction, a non-finite origin, NaN limits or t_min > t_max misses.
  RayHit closestHit(const Ray& ray) const;
  // Whether any surface lies along the ray within [t_min, t_max]; false for an invalid ray.
  bool occluded(const Ray& ray) const;

  // The same two queries as if object `object_index` were alone in the scene at its pose. Throw
  // core::Error on a bad index.
  RayHit closestHitAlone(int object_index, const Ray& ray) const;
  bool occludedAlone(int object_index, const Ray& ray) const;

  // The four queries for many rays at once, result i for rays[i] (occluded: 1, else 0). Embree
  // traces them as packets: several times faster when neighbouring rays are alike, as those
  // through consecutive pixels or those converging on a projector are; meant for such rays.
  // Packet and single-ray kernels round differently, and Embree may switch a ray from one to the
  // other depending on the rest of its batch: where two surfaces lie within float rounding of
  // each other along a ray, or a ray grazes an edge, the answer may differ from the single-ray
  // query's. The same batch always gives the same answers.
  std::vector<RayHit> closestHits(const std::vector<Ray>& rays) const;
  std::vector<uint8_t> occludedEach(const std::vector<Ray>& rays) const;
  std::vector<RayHit> closestHitsAlone(int object_index, const std::vector<Ray>& rays) const;
  std::vector<uint8_t> occludedEachAlone(int object_index, const std::vector<Ray>& rays) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;  // null only in a moved-from caster, which hits nothing
};

}  // namespace binpick::simulation
