#pragma once
// Rotations and translations as other calibration tools store them, and the projector's pose
// relative to the camera composed from where each device saw the calibration board. Errors are
// core::Error without the file's name: the caller adds it and the key.
#include <Eigen/Geometry>
#include <vector>

#include "foreign_storage.hpp"

namespace binpick::io::detail {

// One rotation: a 3x3 matrix (also as 9 values in a row) or a rotation vector (Rodrigues: 3
// values, as a row, a column or a list). A matrix within 1e-3 of a rotation (what printing it to
// a few digits leaves) is replaced by the nearest rotation; farther, it is refused.
Eigen::Matrix3d rotationOf(const StoredNumbers& stored);
// One rotation per board view: one of the above, n rotation vectors (n x 3, n x 3 x 1, a list of
// 3x1) or n matrices (n x 3 x 3, a list of 3x3). A 3x3 that is not a rotation is read as three
// rotation vectors, one per row.
std::vector<Eigen::Matrix3d> rotationsOf(const StoredNumbers& stored);
// One translation (3 values: a row, a column, a list) or one per view (n x 3, n x 3 x 1, a list
// of 3x1), in the file's unit.
Eigen::Vector3d translationOf(const StoredNumbers& stored);
std::vector<Eigen::Vector3d> translationsOf(const StoredNumbers& stored);

// A device's pose of the board in each view: x_device = R x_board + t.
struct BoardViews {
  std::vector<Eigen::Matrix3d> rotations;
  std::vector<Eigen::Vector3d> translations;
};

// T_projector_camera = T_projector_board * T_camera_board^-1 in each view, averaged (the rotation
// nearest the mean matrix, the mean translation). Throws when the devices saw different numbers
// of views, or when one view's composition lies more than 2 degrees or 10% of the baseline from
// the mean: the poses do not belong to the same views in the same order.
Eigen::Isometry3d composeFromBoardViews(const BoardViews& camera, const BoardViews& projector);

}  // namespace binpick::io::detail
