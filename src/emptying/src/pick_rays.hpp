#pragma once
// Rays of the pick judge, in the grasp frame (z along the approach) and traced in the bin frame:
// sample patterns over discs and rectangles, and the swept-volume test of the tool's approach.
// Internal to binpick::emptying. Pure functions: thread-safe.
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "binpick/emptying/pick_truth.hpp"

namespace binpick::emptying::detail {

// Points (x, y) of the grasp frame's xy plane: the centre and rings every `spacing` out to
// `radius`, the last ring exactly at it, each ring's points at most about `spacing` apart.
std::vector<Eigen::Vector2d> discSamples(double radius, double spacing);
// A grid over [x0, x1] x [y0, y1], edges included, points at most `spacing` apart.
std::vector<Eigen::Vector2d> rectangleSamples(double x0, double x1, double y0, double y1, double spacing);

// A column of a solid swept along the approach: at (x, y) of the grasp frame, the solid fills
// z in [z_from, z_to].
struct Column {
  Eigen::Vector2d xy;
  double z_from = 0.0;
  double z_to = 0.0;
};

struct SweepHit {
  bool hit = false;
  int object = -1;  // part index or PickJudgement::kBin
};

// Whether any surface of the scene lies inside the columns (rays along +z of the grasp frame from
// z_from to z_to), and the first column's object that does.
SweepHit sweepHits(const TrueScene& scene, const Eigen::Isometry3d& T_bin_grasp, const std::vector<Column>& columns);

// "<solid> hits part N" or "<solid> hits the bin".
std::string hitReason(const std::string& solid, int object);

// The rays through `points` of the grasp frame along `direction` (grasp frame), traced in the
// bin frame over [0, length].
std::vector<simulation::RayHit> castFrom(const TrueScene& scene, const Eigen::Isometry3d& T_bin_grasp,
                                         const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& direction,
                                         double length);

double degrees(double radians);
// Angle between two unit vectors, degrees, accurate near 0 and 180.
double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

PickJudgement judgeSuction(const TrueScene& scene, const Eigen::Isometry3d& T_bin_grasp,
                           const picking::GripperParams& gripper, double approach_distance,
                           const PickTruthParams& params);
PickJudgement judgeParallel(const TrueScene& scene, const Eigen::Isometry3d& T_bin_grasp,
                            const picking::GripperParams& gripper, double approach_distance, double opening,
                            const PickTruthParams& params);

}  // namespace binpick::emptying::detail
