#pragma once
// Boundary-aware point pairs (Choi et al. 2012, "Voting-based pose estimation for robotic assembly
// using a 3D sensor", surface-to-boundary pairs). Where a part shows one face, all its surface pairs
// share a normal and tell nothing but their length: a thin L strip votes like any flat face of the
// part. The outline does tell: the scene's boundary points (the near side of the organized cloud's
// depth discontinuities, each with the direction of its boundary line) are paired with the voting's
// surface reference points, looked up in a second table built from the model's convex creases,
// and vote into the same accumulator (voting.hpp).
#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "binpick/estimation/detector_params.hpp"
#include "binpick/estimation/hash_table.hpp"
#include "binpick/estimation/model.hpp"
#include "binpick/io/point_cloud.hpp"
#include "scene.hpp"

namespace binpick::estimation {

// Points on lines, each with a unit direction (no sign).
struct BoundaryPoints {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> directions;
  std::size_t size() const { return points.size(); }
};

// The model's convex creases (where the outline of a face seen from the camera lies), one point
// per step, and the surface-to-boundary table of the model's points against them.
struct BoundaryModel {
  BoundaryPoints creases;
  PpfHashTable table;
};

// From the model's fine surface: points with a neighbour within 0.75 step whose normal is turned
// more than the crease angle and which lies behind their tangent plane (convex), subsampled at the
// step, each along its crease (n_i x n_j, averaged over the crease points within a step; none
// where three faces meet).
BoundaryModel prepareBoundaryModel(const PreparedModel& model, const BoundaryParams& params);

// The near side of the organized cloud's depth discontinuities inside the crop, subsampled at the
// model's step, each with the direction of its line (principal axis of the boundary pixels within
// a step). An unorganized cloud has no pixel neighbourhood: no boundary points.
BoundaryPoints sceneBoundaryPoints(const io::PointCloud& cloud, const std::optional<CropBox>& crop,
                                   const PreparedModel& model, const BoundaryParams& params, int threads = 0);

}  // namespace binpick::estimation
