// The virtual cell's hand-eye truth and HandEyeSessionParams::validate.
#include <cmath>

#include "binpick/core/error.hpp"
#include "binpick/simulation/hand_eye_session.hpp"

namespace binpick::simulation {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

Eigen::Matrix3d rotation(double angle_deg, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle_deg * kDegree, axis.normalized()).matrix();
}

// The board's frame placed so that the centre of its squares sits at `centre` of the mount.
// The first and last corners are symmetric about that centre for either board type.
Eigen::Isometry3d boardWithCentreAt(const BoardSpec& spec, const Eigen::Matrix3d& R, const Eigen::Vector3d& centre) {
  const calibration::BoardLayout layout = spec.layout();
  const Eigen::Vector3d c = 0.5 * (layout.cornerPoint(0) + layout.cornerPoint(layout.cornerCount() - 1));
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = centre - R * c;
  return T;
}

bool rigid(const Eigen::Isometry3d& T) {
  const Eigen::Matrix3d& R = T.linear();
  return T.matrix().allFinite() && (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-9 &&
         R.determinant() > 0;
}

void require(bool ok, const char* field, const char* rule, double value) {
  core::requireField(ok, "HandEyeSessionParams", field, rule, value);
}

}  // namespace

Eigen::Isometry3d virtualCellBaseCamera() {
  // Quaternion (w x y z) = (0, 1, 0, 0): half a turn about x, the camera's z pointing down.
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = rotation(180.0, Eigen::Vector3d::UnitX());
  T.translation() = Eigen::Vector3d(0.6, 0.0, 0.9);
  return T;
}

Eigen::Isometry3d virtualCellFlangeBoard(const BoardSpec& board) {
  // The print faces away from the flange (board z = -flange z), turned 25 degrees, slightly
  // tilted on its adapter, its centre 30 mm out and a little off the flange axis.
  const Eigen::Matrix3d R = rotation(25.0, Eigen::Vector3d::UnitZ()) * rotation(3.0, Eigen::Vector3d::UnitY()) *
                            rotation(180.0, Eigen::Vector3d::UnitX());
  return boardWithCentreAt(board, R, Eigen::Vector3d(0.012, -0.008, 0.030));
}

Eigen::Isometry3d virtualCellFlangeCamera() {
  // Looking along the tool axis, turned a quarter turn and tilted 5 degrees towards it.
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = rotation(90.0, Eigen::Vector3d::UnitZ()) * rotation(5.0, Eigen::Vector3d::UnitX());
  T.translation() = Eigen::Vector3d(0.065, -0.020, 0.090);
  return T;
}

Eigen::Isometry3d virtualCellBaseBoard(const BoardSpec& board) {
  // Flat on the table beside the bin, print up (board z down), turned 20 degrees.
  const Eigen::Matrix3d R = rotation(20.0, Eigen::Vector3d::UnitZ()) * rotation(180.0, Eigen::Vector3d::UnitX());
  return boardWithCentreAt(board, R, Eigen::Vector3d(0.55, 0.10, 0.0));
}

void HandEyeSessionParams::validate() const {
  require(views >= 1 && views <= 1000, "views", "in [1, 1000]", views);
  require(std::isfinite(robot_noise_mm) && robot_noise_mm >= 0.0, "robot_noise_mm", ">= 0", robot_noise_mm);
  require(std::isfinite(robot_noise_deg) && robot_noise_deg >= 0.0, "robot_noise_deg", ">= 0", robot_noise_deg);
  board.validate();
  rig.validate();
  poses.validate();
  require(rigid(T_base_camera), "T_base_camera", "a rigid motion", 0);
  require(rigid(T_flange_board), "T_flange_board", "a rigid motion", 0);
  require(rigid(T_flange_camera), "T_flange_camera", "a rigid motion", 0);
  require(rigid(T_base_board), "T_base_board", "a rigid motion", 0);
}

}  // namespace binpick::simulation
