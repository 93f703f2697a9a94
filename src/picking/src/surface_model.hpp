#pragma once
// The part's surface as the grasp generator queries it: seeded, thinned samples with their outward
// normals and smooth patch (face) ids, points to test the gripper's volume against, the centre of
// mass, and rays cast against the surface (triangles of a mesh, or small discs standing for the
// points of a cloud) through a uniform grid. Built once per generation call and immutable after:
// castRay writes only the caller's RayScratch, so threads may share one SurfaceModel, each
// casting with a scratch of its own.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "binpick/picking/grasp_generation.hpp"

namespace binpick::picking {

struct SurfaceSample {
  Eigen::Vector3d point;
  Eigen::Vector3d normal;  // outward, unit
  int patch = 0;           // smooth patch (face) of the surface
};

struct RayHit {
  double distance = 0.0;   // along the ray's unit direction
  Eigen::Vector3d normal;  // outward normal of what was hit
  int patch = 0;
};

// Which primitives the current ray has tested (one listed in several grid cells is tested once).
// One per thread: castRay writes it, and nothing else. Sized by castRay on first use; one scratch
// may serve several models in turn.
class RayScratch {
 private:
  friend class SurfaceModel;
  std::vector<std::uint32_t> visit_stamp_;  // per primitive: the stamp of the last ray that tested it
  std::uint32_t stamp_ = 0;                 // the current ray's; unsigned: its wrap is defined
};

class SurfaceModel {
 public:
  // Throws core::Error when the mesh is invalid or has no area.
  static SurfaceModel fromMesh(const io::TriangleMesh& mesh, const GraspGenerationParams& params);
  // Throws core::Error when the cloud is invalid, empty or has no normals.
  static SurfaceModel fromCloud(const io::PointCloud& cloud, const GraspGenerationParams& params);

  // The first surface crossed within max_distance of `origin` along the unit `direction`, facing
  // either way. Writes `scratch` only: concurrent calls need a scratch each.
  std::optional<RayHit> castRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double max_distance,
                                RayScratch& scratch) const;

  const std::vector<SurfaceSample>& samples() const { return samples_; }
  // Where the part is, for the gripper's volume test: the samples and the mesh vertices.
  const std::vector<Eigen::Vector3d>& obstaclePoints() const { return obstacles_; }
  const Eigen::Vector3d& centreOfMass() const { return centre_of_mass_; }
  double radius() const { return radius_; }  // farthest obstacle point from the centre of mass

  struct Primitive {
    Eigen::Vector3d a, b, c;   // triangle corners; a disc: a = centre, b = c unused
    Eigen::Vector3d normal;    // outward, unit
    double disc_radius = 0.0;  // > 0: a disc (a cloud's point)
    int patch = 0;
  };

 private:
  void buildGrid();
  void cellsOf(const Eigen::Vector3d& low, const Eigen::Vector3d& high, std::vector<int>& cells) const;
  int cellIndex(const Eigen::Vector3d& point) const;

  std::vector<Primitive> primitives_;
  std::vector<SurfaceSample> samples_;
  std::vector<Eigen::Vector3d> obstacles_;
  Eigen::Vector3d centre_of_mass_ = Eigen::Vector3d::Zero();
  double radius_ = 0.0;

  // Uniform grid: each cell lists the primitives whose box, grown by half a cell, overlaps it.
  Eigen::Vector3d grid_origin_ = Eigen::Vector3d::Zero();
  double cell_size_ = 0.0;  // 0: chosen from the extent
  Eigen::Vector3i grid_dims_ = Eigen::Vector3i::Ones();
  std::vector<std::vector<int>> cells_;
};

}  // namespace binpick::picking
