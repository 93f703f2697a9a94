#pragma once
// Hand-eye calibration: where the camera sits relative to the robot, from views that pair a
// robot pose with the board pose the camera measured at that moment.
//   Eye-to-hand: the camera is fixed, the board is held by the flange. Unknowns T_base_camera
//                and T_flange_board.
//   Eye-in-hand: the camera is on the flange, the board is fixed. Unknowns T_flange_camera and
//                T_base_board.
// "Mount" below is the frame each of them is fixed to: the base or the flange.
//
// Robot poses are always T_base_flange, the flange (tool0, no TCP) in the base frame, as a teach
// pendant shows it; the mapping onto OpenCV's conventions (gripper2base, base2gripper,
// world2cam, ...) is done here, so the base->gripper vs gripper->base mix-up cannot be made
// through this API. Poses that were inverted before they got here (flange->base) are detected:
// they are solved as given and inverted, and an inverted set that fits clearly better is an
// error. The same test catches the wrong setup, which amounts to inverting the poses.
// Stateless functions: thread-safe.
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace binpick::calibration {

enum class HandEyeSetup { EyeToHand, EyeInHand };
// "eye-to-hand", "eye-in-hand"; handEyeSetupFromName throws core::Error on another name.
std::string handEyeSetupName(HandEyeSetup setup);
HandEyeSetup handEyeSetupFromName(const std::string& name);
// "T_base_camera" / "T_flange_camera" and "T_flange_board" / "T_base_board".
std::string cameraTransformName(HandEyeSetup setup);
std::string boardTransformName(HandEyeSetup setup);

// OpenCV's solvers. Shah and Li (cv::calibrateRobotWorldHandEye) solve for both unknowns at
// once; the others (cv::calibrateHandEye) solve for the camera's transform from pairs of views,
// and the board's is then the mean over the views. Auto runs every one of them, keeps the one
// whose views fit best (lowest residual RMS in mm) and refines it (HandEyeParams::refine).
enum class HandEyeMethod { Auto, Shah, Li, Tsai, Park, Horaud, Andreff, Daniilidis };
// "auto", "shah", "li", "tsai", "park", "horaud", "andreff", "daniilidis".
std::string handEyeMethodName(HandEyeMethod method);
HandEyeMethod handEyeMethodFromName(const std::string& name);  // throws listing the names
std::vector<HandEyeMethod> allHandEyeMethods();                // OpenCV's: every one but Auto

struct HandEyeView {
  std::string name;                                                  // for messages
  Eigen::Isometry3d T_base_flange = Eigen::Isometry3d::Identity();   // metres
  Eigen::Isometry3d T_camera_board = Eigen::Isometry3d::Identity();  // metres
};

struct HandEyeParams {
  HandEyeSetup setup = HandEyeSetup::EyeToHand;
  HandEyeMethod method = HandEyeMethod::Auto;  // measured in docs/hand-eye.md
  int min_views = 6;                           // OpenCV needs 3; 6 leaves room to see a bad view
  // Motion the views must hold, or the rotation (and the translation along a lone rotation
  // axis) is unobservable: the largest rotation between two views, and the spread of the
  // rotation axes (RMS rotation about the second principal axis of all pairwise rotations).
  double min_rotation_deg = 15.0;
  double min_axis_spread_deg = 3.0;
  // The poses count as inverted when, inverted, their RMS residual (mm and degrees) is this
  // many times smaller than as given.
  double inverted_fit_ratio = 3.0;
  // A view is an outlier when its residual exceeds outlier_factor times the median residual
  // and the floor (mm or degrees): the floors keep near-perfect sessions quiet.
  double outlier_factor = 3.0;
  double outlier_floor_mm = 1.0;
  double outlier_floor_deg = 0.2;
  // A view disagrees with the others when, solved without it, its residual stands above the
  // others' by more than outlier_mad_factor robust standard deviations (1.4826 MAD) as well as
  // the limits above. One wrong pose pulls the solution towards itself, so this compares each
  // view with the solution of the others. drop_outliers leaves such views out and solves again
  // (once, and only while min_views remain); otherwise they are warned about.
  double outlier_mad_factor = 4.0;
  bool drop_outliers = false;
  // A residual RMS above this is warned about (below max_rms_mm, which fails): a good arm leaves
  // 0.2 to 4 mm (docs/hand-eye.md). The board's distances are then fitted with a scale, and a
  // scale that fits much better is named: a wrong board size costs millimetres.
  double warn_rms_mm = 5.0;
  // A calibration whose RMS residual exceeds these fails: the views disagree by as much. Eye-in-
  // hand, the robot's orientation error shows at the board times the ~1 m flange-to-board
  // distance (0.2 deg: 3.5 mm); a wrong board size or a swapped image shows far above.
  double max_rms_mm = 10.0;
  double max_rms_deg = 1.0;
  // Gauss-Newton on both transforms after OpenCV's solution, minimising how far each reported
  // flange pose is from the one the camera predicts. Measured (docs/hand-eye.md): eye-to-hand it
  // cuts the error severalfold; eye-in-hand the board pose's error reaches the flange times the
  // camera-to-board distance, and with a coarse camera it made the result worse. Auto always
  // refines; with another method it is opt-in.
  bool refine = false;
  void validate() const;  // throws core::Error naming the field
};

// How far the two ways to the board disagree in one view: the robot's (T_base_flange and the
// mount transforms) and the camera's (T_camera_board). Translation between the board origins.
struct HandEyeResidual {
  std::string name;
  double translation_mm = 0.0;
  double rotation_deg = 0.0;
  bool outlier = false;
  bool dropped = false;  // left out of the solution (drop_outliers); not in the RMS
};

struct HandEyeResult {
  HandEyeSetup setup = HandEyeSetup::EyeToHand;
  HandEyeMethod method = HandEyeMethod::Auto;  // as asked
  HandEyeMethod start = HandEyeMethod::Shah;   // OpenCV's method the solution started from
  bool refined = false;
  Eigen::Isometry3d T_mount_camera = Eigen::Isometry3d::Identity();  // cameraTransformName
  Eigen::Isometry3d T_mount_board = Eigen::Isometry3d::Identity();   // boardTransformName
  std::vector<HandEyeResidual> residuals;                            // one per view, input order
  std::vector<std::string> dropped;                                  // views left out (drop_outliers)
  double rms_mm = 0.0;                                               // over the views kept
  double rms_deg = 0.0;
  std::vector<std::string> warnings;  // outliers by name, a board size that looks wrong
  // Why the calibration must not be used (RMS above max_rms_*); empty when it is good.
  std::string failure;
  bool ok() const { return failure.empty(); }
};

// Throws core::Error on bad params, fewer than min_views views, a non-rigid or non-finite
// pose (naming the view), too little or single-axis rotation, inverted poses, robot positions
// that fit as metres, or an OpenCV solution that is not finite. A poor fit is not thrown: the result says so in
// `failure`, with the residuals that show which views are to blame.
HandEyeResult solveHandEye(const std::vector<HandEyeView>& views, const HandEyeParams& params);

// The residuals of given transforms (no solving): for a solution, or the truth.
std::vector<HandEyeResidual> handEyeResiduals(const std::vector<HandEyeView>& views, HandEyeSetup setup,
                                              const Eigen::Isometry3d& T_mount_camera,
                                              const Eigen::Isometry3d& T_mount_board);

// Translation (mm) and rotation (degrees) between two poses: |t_a - t_b| and the angle of
// R_a^T R_b. For errors of a recovered transform against the truth.
struct PoseDifference {
  double translation_mm = 0.0;
  double rotation_deg = 0.0;
};
PoseDifference poseDifference(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);

// "shah", "shah+refine", "auto (park+refine)": how a result was computed.
std::string handEyeMethodDescription(const HandEyeResult& result);

}  // namespace binpick::calibration
