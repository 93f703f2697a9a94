// Which parts of a board the rig sees: corners for the truth, the outline for the pose draws.
#include <vector>

#include "binpick/simulation/calibration_board.hpp"
#include "render/lens_bounds.hpp"

namespace binpick::simulation {
namespace {

// Points along the outline of the printed face, corners included: lens distortion bends the
// projected edges, so the corners alone do not bound the board's image.
constexpr int kOutlineSamplesPerEdge = 16;
// How far past the image the distortion polynomial is trusted to be one-to-one.
constexpr double kFieldMargin = 0.1;

std::vector<Eigen::Vector3d> outline(const Eigen::AlignedBox2d& face) {
  const Eigen::Vector2d corners[4] = {
      face.corner(Eigen::AlignedBox2d::BottomLeft), face.corner(Eigen::AlignedBox2d::BottomRight),
      face.corner(Eigen::AlignedBox2d::TopRight), face.corner(Eigen::AlignedBox2d::TopLeft)};
  std::vector<Eigen::Vector3d> points;
  for (int edge = 0; edge < 4; ++edge) {
    for (int k = 0; k < kOutlineSamplesPerEdge; ++k) {
      const double f = static_cast<double>(k) / kOutlineSamplesPerEdge;
      const Eigen::Vector2d p = (1.0 - f) * corners[edge] + f * corners[(edge + 1) % 4];
      points.emplace_back(p.x(), p.y(), 0.0);
    }
  }
  return points;
}

// A device (camera or projector) as seen from the camera frame.
struct Device {
  const io::LensIntrinsics& lens;
  Eigen::Isometry3d T_device_camera;
  Eigen::AlignedBox2d field;  // normalised coordinates the lens maps one-to-one

  Device(const io::LensIntrinsics& l, const Eigen::Isometry3d& T)
      : lens(l), T_device_camera(T), field(detail::normalisedImageBounds(l, kFieldMargin)) {}

  Eigen::Vector3d centreInCamera() const { return T_device_camera.inverse().translation(); }

  // Projects a camera-frame point; false when it is behind the device, outside the field or
  // closer than `margin` pixels to the image border.
  bool sees(const Eigen::Vector3d& point_camera, double margin, Eigen::Vector2d* pixel) const {
    const Eigen::Vector3d p = T_device_camera * point_camera;
    if (!(p.z() > 0.0) || !field.contains(Eigen::Vector2d(p.x() / p.z(), p.y() / p.z()))) {
      return false;
    }
    *pixel = lens.project(p);
    return pixel->x() >= margin - 0.5 && pixel->y() >= margin - 0.5 && pixel->x() <= lens.width - 0.5 - margin &&
           pixel->y() <= lens.height - 0.5 - margin;
  }
};

// Cosine between the print's normal (-z of the board) and the direction to `centre`.
double facingCosine(const Eigen::Isometry3d& T_camera_board, const Eigen::Vector3d& point_camera,
                    const Eigen::Vector3d& centre) {
  const Eigen::Vector3d normal = -T_camera_board.linear().col(2);
  return normal.dot((centre - point_camera).normalized());
}

}  // namespace

std::vector<CornerObservation> observeCorners(const CalibrationBoard& board, const io::RigCalibration& rig,
                                              const Eigen::Isometry3d& T_camera_board) {
  const Device camera(rig.camera, Eigen::Isometry3d::Identity());
  const Device projector(rig.projector, rig.T_projector_camera);
  std::vector<CornerObservation> seen;
  for (const BoardCorner& corner : board.corners()) {
    const Eigen::Vector3d p = T_camera_board * corner.point;
    CornerObservation o;
    o.id = corner.id;
    if (facingCosine(T_camera_board, p, camera.centreInCamera()) > 0.0 &&
        facingCosine(T_camera_board, p, projector.centreInCamera()) > 0.0 && camera.sees(p, 0.0, &o.camera_pixel) &&
        projector.sees(p, 0.0, &o.projector_pixel)) {
      seen.push_back(o);
    }
  }
  return seen;
}

bool boardInView(const CalibrationBoard& board, const io::RigCalibration& rig, const Eigen::Isometry3d& T_camera_board,
                 double image_margin, double min_facing_cosine) {
  const Device camera(rig.camera, Eigen::Isometry3d::Identity());
  const Device projector(rig.projector, rig.T_projector_camera);
  Eigen::Vector2d pixel;
  for (const Eigen::Vector3d& point : outline(board.printedFace())) {
    const Eigen::Vector3d p = T_camera_board * point;
    if (!camera.sees(p, image_margin, &pixel) || !projector.sees(p, image_margin, &pixel)) {
      return false;
    }
    if (facingCosine(T_camera_board, p, camera.centreInCamera()) < min_facing_cosine ||
        facingCosine(T_camera_board, p, projector.centreInCamera()) < min_facing_cosine) {
      return false;
    }
  }
  return true;
}

}  // namespace binpick::simulation
