#pragma once
// The measured cloud against the tool: does the gripper (gripper.hpp), moved straight along its
// approach onto a grasp, run into anything the camera saw, and how much room is left around it.
//
// MeasuredScene holds the cloud in the robot base frame, thinned to about `thin_step` (one point
// per thin_step column of the base xy plane and per thin_step of height) and indexed as a grid
// of such columns, each column's points sorted by height. A query visits only the columns under
// the tool's bounding box (grown by the clearance cap) and, in each, only the heights the box
// spans. Built once per cycle, immutable afterwards: thread-safe to query from many threads.
//
// The tool's volume in the grasp frame (z: the approach, into the part; all grown by `margin`):
// - suction: the cup, radius cup_diameter / 2, from z = -margin (points on the grasped face under
//   the cup are the seal, not a collision) back to z = -cup_length, swept back along the approach
//   by approach_distance; the body, radius tool_radius, from z = -cup_length back by tool_length
//   + approach_distance (the tool is at the pre-grasp point before it moves straight in).
// - parallel: two fingers, boxes finger_thickness x finger_width x finger_depth with their
//   contact faces `opening` apart along x, swept back by approach_distance; the body from the
//   fingers' root (z = -finger_depth / 2) back by tool_length + approach_distance.
// Clearance: the distance from that volume to the nearest measured point outside it, capped. The
// grasped face in front of the cup (z > -margin) and the part between the jaws (|x| inside the
// opening) are what the tool touches on purpose: they count for the body, not for the cup or the
// fingers.
#include <Eigen/Geometry>
#include <algorithm>
#include <cstdint>
#include <vector>

#include "binpick/io/point_cloud.hpp"
#include "binpick/picking/gripper.hpp"

namespace binpick::picking {

struct MeasuredSceneParams {
  double thin_step = 0.003;  // metres: column size and height step of the thinned cloud
  void validate() const;     // throws core::Error naming the field
};

class MeasuredScene {
 public:
  // `cloud`: camera frame, metres, organized or not, NaN points skipped. Organized clouds are
  // first strided in pixels so that neighbours stay about thin_step / 2 apart (fast on 1.3 MP).
  // Stray points far beyond the bulk of the cloud in base xy (further from its 1st-99th
  // percentile box than the box is wide, and at least 1 m) are skipped too: no tool reaches
  // them, and the grid stays as fine as the bulk needs. Memory is bounded whatever the points:
  // at most about 2^20 columns (they grow beyond that), 2^14 along a side.
  // Throws core::Error for a non-rigid T_base_camera or invalid params.
  MeasuredScene(const io::PointCloud& cloud, const Eigen::Isometry3d& T_base_camera,
                const MeasuredSceneParams& params = {});

  std::size_t size() const { return points_.size(); }                     // points kept after thinning
  const std::vector<Eigen::Vector3f>& points() const { return points_; }  // base frame

  // Visits the points in the box [lo, hi] (base frame), and maybe a few just outside it in xy:
  // `visit(point)` returns false to stop. Returns false when stopped.
  template <typename Visit>
  bool visitBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, Visit&& visit) const;

  // Of the columns within `radius` (base xy) of `point` that hold any measured point, the share
  // whose highest point lies more than `height` above point.z(): 0 = nothing above, 1 = buried.
  double shareCoveredAbove(const Eigen::Vector3d& point, double radius, double height) const;

 private:
  struct CellRange {
    int x0, x1, y0, y1;  // inclusive, clipped to the grid; empty when x0 > x1 or y0 > y1
  };
  CellRange cellsUnder(double x_lo, double y_lo, double x_hi, double y_hi) const;
  void thinColumns(double step);

  double cell_size_ = 0.003;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();  // base xy of cell (0, 0)'s corner
  int columns_ = 0, rows_ = 0;
  std::vector<std::uint32_t> cell_start_;  // columns_ * rows_ + 1 offsets into points_
  std::vector<Eigen::Vector3f> points_;    // by cell, then by ascending z
  std::vector<float> heights_;             // points_[i].z(), for the binary search
};

// How the tool moves onto the grasp and how close counts, for toolCollision.
struct ToolSweep {
  double approach_distance = 0.10;  // metres: straight approach from the pre-grasp point
  double margin = 0.002;            // metres: the tool's volume grown by this much
  double opening = 0.0;             // parallel: metres between the contact faces; <= 0: stroke
  double clearance_cap = 0.02;      // metres: clearances are reported up to this
};

struct ToolContact {
  bool collision = false;  // a measured point inside the tool's volume
  double clearance = 0.0;  // metres to the nearest point outside it, capped; 0 on collision
};

// Whether the gripper, swept along its approach onto T_base_grasp, holds a measured point.
// Well under a millisecond on a thinned 1.3 MP cloud; stops at the first point inside.
ToolContact toolCollision(const MeasuredScene& scene, const Eigen::Isometry3d& T_base_grasp,
                          const GripperParams& gripper, const ToolSweep& sweep);

// ---------------------------------------------------------------------------------------------

template <typename Visit>
bool MeasuredScene::visitBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, Visit&& visit) const {
  const CellRange cells = cellsUnder(lo.x(), lo.y(), hi.x(), hi.y());
  const auto z_lo = static_cast<float>(lo.z());
  const auto z_hi = static_cast<float>(hi.z());
  for (int y = cells.y0; y <= cells.y1; ++y) {
    for (int x = cells.x0; x <= cells.x1; ++x) {
      const std::size_t cell =
          static_cast<std::size_t>(y) * static_cast<std::size_t>(columns_) + static_cast<std::size_t>(x);
      const auto begin = heights_.begin() + cell_start_[cell];
      const auto end = heights_.begin() + cell_start_[cell + 1];
      for (auto it = std::lower_bound(begin, end, z_lo); it != end && *it <= z_hi; ++it) {
        if (!visit(points_[static_cast<std::size_t>(it - heights_.begin())])) return false;
      }
    }
  }
  return true;
}

}  // namespace binpick::picking
