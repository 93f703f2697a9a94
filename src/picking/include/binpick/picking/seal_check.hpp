#pragma once
// Does the cup seal where the camera looked? Before a suction pick is handed out, the measured
// surface under the cup is read straight from the organized cloud: each sample of the cup's disc
// (and a rim just beyond it) is projected into the camera, and the point measured at that pixel
// must lie on the grasp plane within the seal tolerance. A detection off by a few millimetres puts
// part of the disc over an edge, a gap or a neighbour, and the samples there measure another
// depth; a wrong pose puts the disc where no face is. The tool-collision test (tool_collision.hpp)
// cannot see this: it only keeps the tool clear of what rises above the grasp plane.
// A flat-lying part's pose is least sure along its face (its outline fixes it there): a cup that
// misses the face's edge by a millimetre is slid along the face, in steps of shift_step up to
// max_shift, to the nearest place where the measured surface seals (findSeal). The measured
// surface must also face the cup: the plane fitted to the seen samples within max_angle_deg of
// square to the approach.
// Immutable once built: thread-safe to query.
#include <Eigen/Geometry>
#include <optional>

#include "binpick/io/lens.hpp"
#include "binpick/io/point_cloud.hpp"

namespace binpick::picking {

struct SealCheckParams {
  double rim_margin = 0.0005;    // metres: the disc is checked out to its radius + this
  double noise = 0.0005;         // metres added to the gripper's seal tolerance (measurement noise)
  double max_shift = 0.002;      // metres the cup may be slid along the face to find a seal (0: never)
  double shift_step = 0.001;     // metres between the places tried
  double min_seen_share = 0.95;  // of the samples, the share that must hold a measured point (edges
                                 // often measure nothing: a shadow, a mixed pixel filtered out)
  // Degrees between the approach and the normal of the plane fitted to the measured samples. On
  // a thin shaft the tolerance in depth cannot see the cup off its top line: 1 mm of pose error on
  // a 10 mm shaft turns the surface 11 degrees under a 4 mm cup and leaves it 0.5 mm at the rim.
  double max_angle_deg = 8.0;
  void validate() const;  // throws core::Error naming the field
};

struct SealCheck {
  bool seals = false;
  double seen_share = 0.0;       // samples whose pixel holds a measured point
  double worst_deviation = 0.0;  // metres, the largest |distance| of a seen sample from the plane
  double angle_deg = 0.0;        // the measured surface's normal against the approach
};

class MeasuredSurface {
 public:
  // `cloud`: organized, camera frame (width x height of `camera`), NaN where nothing was measured.
  // Throws core::Error when the cloud is not organized to the camera's size or the camera is
  // invalid. Both must outlive the object.
  MeasuredSurface(const io::PointCloud& cloud, const io::LensIntrinsics& camera,
                  const Eigen::Isometry3d& T_base_camera);

  // The disc of `radius` in the grasp frame's xy plane at T_base_grasp (grasp frame: gripper.hpp),
  // measured within `tolerance` + params.noise.
  SealCheck check(const Eigen::Isometry3d& T_base_grasp, double radius, double tolerance,
                  const SealCheckParams& params) const;

  // The grasp itself when it seals, else the nearest grasp slid along its xy plane (rings of
  // shift_step out to max_shift, 8 places per millimetre of ring) that does; none when none does.
  std::optional<Eigen::Isometry3d> findSeal(const Eigen::Isometry3d& T_base_grasp, double radius, double tolerance,
                                            const SealCheckParams& params) const;

 private:
  const io::PointCloud& cloud_;
  const io::LensIntrinsics& camera_;
  Eigen::Isometry3d T_camera_base_;
};

}  // namespace binpick::picking
