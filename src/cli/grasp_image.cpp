#include "grasp_image.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "binpick/core/error.hpp"
#include "binpick/io/image_file.hpp"

namespace binpick::cli {
namespace {

constexpr int kViewSize = 520;  // pixels per view; four views in a 2 x 2 grid

struct View {
  const char* title;
  Eigen::Matrix3d R_view_model;  // rows: screen right, screen down, into the screen
};

// Looking along `forward` (into the screen) with `up` towards the top of the view.
View lookingAlong(const char* title, const Eigen::Vector3d& forward, const Eigen::Vector3d& up) {
  const Eigen::Vector3d f = forward.normalized();
  const Eigen::Vector3d right = f.cross(up).normalized();
  const Eigen::Vector3d down = f.cross(right);
  View view{title, Eigen::Matrix3d::Identity()};
  view.R_view_model.row(0) = right;
  view.R_view_model.row(1) = down;
  view.R_view_model.row(2) = f;
  return view;
}

class Projection {
 public:
  Projection(const Eigen::Matrix3d& R_view_model, const Eigen::Vector3d& centre, double radius, cv::Point origin)
      : R_(R_view_model), centre_(centre), scale_(0.46 * kViewSize / std::max(radius, 1e-6)), origin_(origin) {}
  cv::Point operator()(const Eigen::Vector3d& model_point) const {
    const Eigen::Vector3d v = R_ * (model_point - centre_);
    return {origin_.x + static_cast<int>(std::lround(kViewSize / 2.0 + scale_ * v.x())),
            origin_.y + static_cast<int>(std::lround(kViewSize / 2.0 + scale_ * v.y()))};
  }
  double depth(const Eigen::Vector3d& model_point) const { return R_.row(2).dot(model_point - centre_); }
  double pixelsPerMetre() const { return scale_; }

 private:
  Eigen::Matrix3d R_;
  Eigen::Vector3d centre_;
  double scale_;
  cv::Point origin_;
};

// Painter's algorithm: far triangles first, grey by how squarely they face the light.
void drawModel(cv::Mat& image, const io::ModelGeometry& model, const Projection& project,
               const Eigen::Vector3d& forward) {
  const Eigen::Vector3d light = (-forward + Eigen::Vector3d(0.3, 0.2, 0.4)).normalized();
  if (!model.hasMesh()) {
    for (const Eigen::Vector3f& p : model.cloud.points) {
      if (p.allFinite()) cv::circle(image, project(p.cast<double>()), 1, cv::Scalar(150, 150, 150), cv::FILLED);
    }
    return;
  }
  std::vector<std::pair<double, std::size_t>> order;
  for (std::size_t t = 0; t < model.mesh.triangles.size(); ++t) {
    const Eigen::Vector3i& tri = model.mesh.triangles[t];
    const Eigen::Vector3d centre =
        (model.mesh.vertices[tri[0]] + model.mesh.vertices[tri[1]] + model.mesh.vertices[tri[2]]).cast<double>() / 3.0;
    order.emplace_back(-project.depth(centre), t);
  }
  std::sort(order.begin(), order.end());
  for (const auto& [depth, t] : order) {
    const Eigen::Vector3i& tri = model.mesh.triangles[t];
    const Eigen::Vector3d a = model.mesh.vertices[tri[0]].cast<double>(),
                          b = model.mesh.vertices[tri[1]].cast<double>(),
                          c = model.mesh.vertices[tri[2]].cast<double>();
    const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
    if (!normal.allFinite() || normal.dot(forward) > 0.0) continue;  // faces away
    const double shade = 70.0 + 150.0 * std::max(0.0, normal.dot(light));
    const std::vector<cv::Point> corners{project(a), project(b), project(c)};
    cv::fillConvexPoly(image, corners, cv::Scalar(shade, shade, shade * 0.95), cv::LINE_AA);
  }
}

double arrowLength(const picking::GripperParams& gripper) {
  return gripper.type == picking::GripperType::Suction ? 1.5 * gripper.cup_diameter : 1.5 * gripper.finger_depth;
}

cv::Scalar colourOfRank(std::size_t rank, std::size_t count) {
  // Best green, worst red, through yellow.
  const double t = count > 1 ? static_cast<double>(rank) / static_cast<double>(count - 1) : 0.0;
  return cv::Scalar(30, 220 * (1.0 - 0.6 * t), 60 + 195 * t);
}

std::vector<cv::Point> projectedLoop(const Projection& project, const std::vector<Eigen::Vector3d>& loop) {
  std::vector<cv::Point> pixels;
  for (const Eigen::Vector3d& p : loop) pixels.push_back(project(p));
  return pixels;
}

// Half the distance between the jaws' contact faces: where the closing line through the grasp
// point leaves the mesh farthest out (a cloud: its farthest point within the fingers' footprint).
double contactHalfWidth(const io::ModelGeometry& model, const Eigen::Isometry3d& T_model_grasp,
                        const picking::GripperParams& gripper) {
  const Eigen::Isometry3d T_grasp_model = T_model_grasp.inverse();
  double half = 0.0;
  if (!model.hasMesh()) {
    for (const Eigen::Vector3f& p : model.cloud.points) {
      const Eigen::Vector3d local = T_grasp_model * p.cast<double>();
      if (std::abs(local.y()) <= 0.5 * gripper.finger_width && std::abs(local.z()) <= 0.5 * gripper.finger_depth) {
        half = std::max(half, std::abs(local.x()));
      }
    }
    return half;
  }
  for (const Eigen::Vector3i& tri : model.mesh.triangles) {
    const Eigen::Vector3d a = T_grasp_model * model.mesh.vertices[tri[0]].cast<double>();
    const Eigen::Vector3d b = T_grasp_model * model.mesh.vertices[tri[1]].cast<double>();
    const Eigen::Vector3d c = T_grasp_model * model.mesh.vertices[tri[2]].cast<double>();
    // The line y = z = 0: barycentric coordinates of the origin in the triangle's yz projection.
    const double det = (b.y() - a.y()) * (c.z() - a.z()) - (c.y() - a.y()) * (b.z() - a.z());
    if (std::abs(det) < 1e-18) continue;
    const double u = (-a.y() * (c.z() - a.z()) + a.z() * (c.y() - a.y())) / det;
    const double v = (-a.z() * (b.y() - a.y()) + a.y() * (b.z() - a.z())) / det;
    if (u < 0 || v < 0 || u + v > 1) continue;
    half = std::max(half, std::abs(a.x() + u * (b.x() - a.x()) + v * (c.x() - a.x())));
  }
  return half;
}

void drawGrasp(cv::Mat& image, const Projection& project, const picking::Grasp& grasp, std::size_t rank,
               std::size_t count, const picking::GripperParams& gripper, double half_opening) {
  const Eigen::Isometry3d& T = grasp.T_model_grasp;
  const cv::Scalar colour = colourOfRank(rank, count);
  std::vector<std::vector<cv::Point>> outlines;
  double arrow_length = 0.0;
  if (gripper.type == picking::GripperType::Suction) {
    const double radius = 0.5 * gripper.cup_diameter;
    std::vector<Eigen::Vector3d> disc;
    for (int k = 0; k < 32; ++k) {
      const double a = 2.0 * M_PI * k / 32;
      disc.push_back(T * Eigen::Vector3d(radius * std::cos(a), radius * std::sin(a), 0.0));
    }
    outlines.push_back(projectedLoop(project, disc));
    arrow_length = arrowLength(gripper);
  } else {
    const double width = 0.5 * gripper.finger_width, depth = 0.5 * gripper.finger_depth;
    // The finger pads where they touch the part, either side of the grasp point along x.
    for (double side : {-1.0, 1.0}) {
      const double x = side * half_opening;
      outlines.push_back(
          projectedLoop(project, {T * Eigen::Vector3d(x, -width, -depth), T * Eigen::Vector3d(x, width, -depth),
                                  T * Eigen::Vector3d(x, width, depth), T * Eigen::Vector3d(x, -width, depth)}));
    }
    arrow_length = arrowLength(gripper);
  }
  cv::Mat overlay = image.clone();
  for (const auto& outline : outlines)
    cv::fillPoly(overlay, std::vector<std::vector<cv::Point>>{outline}, colour, cv::LINE_AA);
  cv::addWeighted(overlay, 0.45, image, 0.55, 0.0, image);
  for (const auto& outline : outlines) cv::polylines(image, outline, true, colour, 2, cv::LINE_AA);
  const cv::Point tip = project(T.translation());
  const cv::Point tail = project(T * Eigen::Vector3d(0, 0, -arrow_length));
  cv::arrowedLine(image, tail, tip, colour, 2, cv::LINE_AA, 0, 0.25);
  const std::string label = std::to_string(rank + 1);
  cv::putText(image, label, tail + cv::Point(4, -4), cv::FONT_HERSHEY_SIMPLEX, 0.55, cv::Scalar(0, 0, 0), 3,
              cv::LINE_AA);
  cv::putText(image, label, tail + cv::Point(4, -4), cv::FONT_HERSHEY_SIMPLEX, 0.55, colour, 1, cv::LINE_AA);
}

}  // namespace

void writeGraspImage(const std::string& path, const io::ModelGeometry& model, const std::vector<picking::Grasp>& grasps,
                     const picking::GripperParams& gripper) {
  const std::vector<Eigen::Vector3f>& points = model.hasMesh() ? model.mesh.vertices : model.cloud.points;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300), high = Eigen::Vector3d::Constant(-1e300);
  for (const Eigen::Vector3f& p : points) {
    if (!p.allFinite()) continue;
    low = low.cwiseMin(p.cast<double>());
    high = high.cwiseMax(p.cast<double>());
  }
  if (!(low.array() <= high.array()).all()) throw core::Error(path + ": the model has no points to draw");
  const Eigen::Vector3d centre = 0.5 * (low + high);
  // Room around the part for the approach arrows.
  const double radius = 0.5 * (high - low).norm() + 0.5 * arrowLength(gripper);
  const std::vector<View> views{lookingAlong("from +z (above)", -Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY()),
                                lookingAlong("from -z (below)", Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY()),
                                lookingAlong("from +x -y +z", Eigen::Vector3d(-1, 1, -0.9), Eigen::Vector3d::UnitZ()),
                                lookingAlong("from -x +y -z", Eigen::Vector3d(1, -1, 0.9), -Eigen::Vector3d::UnitZ())};
  cv::Mat image(2 * kViewSize, 2 * kViewSize, CV_8UC3, cv::Scalar(255, 255, 255));
  for (std::size_t v = 0; v < views.size(); ++v) {
    const cv::Point origin(static_cast<int>(v % 2) * kViewSize, static_cast<int>(v / 2) * kViewSize);
    const Projection project(views[v].R_view_model, centre, radius, origin);
    const Eigen::Vector3d forward = views[v].R_view_model.row(2).transpose();
    drawModel(image, model, project, forward);
    // Worst first, so that the best grasps are drawn on top; only those approaching from this side.
    for (std::size_t i = grasps.size(); i-- > 0;) {
      if (grasps[i].T_model_grasp.linear().col(2).dot(forward) > 0.15) {
        const double half_opening = gripper.type == picking::GripperType::Parallel
                                        ? contactHalfWidth(model, grasps[i].T_model_grasp, gripper)
                                        : 0.0;
        drawGrasp(image, project, grasps[i], i, grasps.size(), gripper, half_opening);
      }
    }
    cv::rectangle(image, cv::Rect(origin, cv::Size(kViewSize, kViewSize)), cv::Scalar(200, 200, 200), 1);
    cv::putText(image, views[v].title, origin + cv::Point(10, 24), cv::FONT_HERSHEY_SIMPLEX, 0.6,
                cv::Scalar(40, 40, 40), 1, cv::LINE_AA);
  }
  const std::string legend = std::to_string(grasps.size()) + " " + picking::gripperTypeName(gripper.type) +
                             " grasps, numbered by rank (green best)";
  cv::putText(image, legend, cv::Point(10, 2 * kViewSize - 12), cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(40, 40, 40),
              1, cv::LINE_AA);
  io::writeImageFile(path, image);
}

}  // namespace binpick::cli
