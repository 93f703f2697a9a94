// The tool's volume in the grasp frame and the distances to it (tool_volume.hpp).
#include "tool_volume.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace binpick::picking {
namespace {

ToolVolume suctionVolume(const GripperParams& g, const ToolSweep& s) {
  ToolVolume tool;
  const double m = s.margin;
  tool.cylinders[0] = {0.5 * g.cup_diameter + m, -(g.cup_length + s.approach_distance) - m, -m, true};
  tool.cylinder_count = 1;
  if (g.bent()) {
    // Grown by the margin at both ends too: it starts a margin before the back of the cup.
    tool.bent_body = BentBody{g.bodyStart() - m * g.bodyAxis(), g.bodyAxis(), g.tool_radius + m, g.tool_length + 2 * m,
                              s.approach_distance};
    return tool;
  }
  tool.cylinders[1] = {g.tool_radius + m, -(g.toolBack() + s.approach_distance) - m, std::min(-g.cup_length + m, -m),
                       false};
  tool.cylinder_count = 2;
  return tool;
}

ToolVolume parallelVolume(const GripperParams& g, const ToolSweep& s) {
  ToolVolume tool;
  const double m = s.margin;
  const double opening = g.jawOpening(s.opening);
  const double root = -0.5 * g.finger_depth;
  const double inner = 0.5 * opening;
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? 1.0 : -1.0;
    const double x_a = sign * (inner - m), x_b = sign * (inner + g.finger_thickness + m);
    Box& finger = tool.boxes[static_cast<std::size_t>(side)];
    finger.lo = {std::min(x_a, x_b), -0.5 * g.finger_width - m, root - s.approach_distance - m};
    finger.hi = {std::max(x_a, x_b), 0.5 * g.finger_width + m, -root + m};
    finger.between_jaws = inner;
  }
  tool.box_count = 2;
  tool.cylinders[0] = {g.tool_radius + m, -(g.toolBack() + s.approach_distance) - m, root + m, false};
  tool.cylinder_count = 1;
  return tool;
}

// Signed distance from `p` to the body at one point of its sweep, moved back along the
// approach by `back` (negative inside): a finite cylinder's, exact.
double bentBodySignedDistance(const BentBody& body, const Eigen::Vector3d& p, double back) {
  const Eigen::Vector3d q = p + back * Eigen::Vector3d::UnitZ() - body.start;
  const double along = q.dot(body.axis);
  const double radial = (q - along * body.axis).norm() - body.radius;
  const double axial = std::max(-along, along - body.length);
  if (radial <= 0.0 && axial <= 0.0) return std::max(radial, axial);
  const double r = std::max(radial, 0.0), a = std::max(axial, 0.0);
  return std::sqrt(r * r + a * a);
}

// Distance from `p` to the segment from `a` to `b`.
double segmentDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-30), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

// Distance from `p` to the body's axis swept along the approach, a parallelogram: in the plane of
// its two edges when p projects inside it, else to the nearest edge.
double sweptAxisDistance(const BentBody& body, const Eigen::Vector3d& p) {
  const Eigen::Vector3d back = -Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d q = p - body.start;
  // Least squares for q = along * axis + behind * back (axis and back are unit, not parallel).
  const double cross = body.axis.dot(back), det = 1.0 - cross * cross;
  const double qa = q.dot(body.axis), qb = q.dot(back);
  const double along = (qa - cross * qb) / det, behind = (qb - cross * qa) / det;
  if (along >= 0.0 && along <= body.length && behind >= 0.0 && behind <= body.sweep) {
    return (q - along * body.axis - behind * back).norm();
  }
  const Eigen::Vector3d end = body.start + body.length * body.axis, swept = body.sweep * back;
  return std::min({segmentDistance(p, body.start, end), segmentDistance(p, body.start + swept, end + swept),
                   segmentDistance(p, body.start, body.start + swept), segmentDistance(p, end, end + swept)});
}

}  // namespace

// Distance from `p` (grasp frame) to the cylinder; negative when inside. `counts` tells whether
// the distance matters for the clearance.
double cylinderDistance(const Cylinder& c, const Eigen::Vector3d& p, bool& counts) {
  const double radial = std::sqrt(p.x() * p.x() + p.y() * p.y()) - c.radius;
  const double axial = std::max(c.z_lo - p.z(), p.z() - c.z_hi);
  if (radial <= 0.0 && axial <= 0.0) return -1.0;
  counts = !(c.front_is_contact && p.z() > c.z_hi);
  const double r = std::max(radial, 0.0), a = std::max(axial, 0.0);
  return std::sqrt(r * r + a * a);  // not std::hypot: its overflow care costs 5x here
}

// Distance from `p` to the swept body (negative inside), or `beyond` when it is at least that far.
// The swept axis grown by the radius holds the swept body, so most points are settled by it
// alone. Otherwise the least over the sweep: a convex body's signed distance is convex along a
// straight line, so a golden-section search finds it; 24 steps narrow a 0.1 m sweep to 10
// micrometres.
double bentBodyDistance(const BentBody& body, const Eigen::Vector3d& p, double beyond) {
  if (sweptAxisDistance(body, p) - body.radius >= beyond) return beyond;
  constexpr int kSteps = 24;
  const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
  double lo = 0.0, hi = body.sweep;
  double a = hi - ratio * (hi - lo), b = lo + ratio * (hi - lo);
  double fa = bentBodySignedDistance(body, p, a), fb = bentBodySignedDistance(body, p, b);
  for (int step = 0; step < kSteps && fa >= 0.0 && fb >= 0.0; ++step) {
    if (fa < fb) {
      hi = b, b = a, fb = fa;
      a = hi - ratio * (hi - lo);
      fa = bentBodySignedDistance(body, p, a);
    } else {
      lo = a, a = b, fa = fb;
      b = lo + ratio * (hi - lo);
      fb = bentBodySignedDistance(body, p, b);
    }
  }
  return std::min({fa, fb, bentBodySignedDistance(body, p, 0.0), bentBodySignedDistance(body, p, body.sweep)});
}

double boxDistance(const Box& b, const Eigen::Vector3d& p, bool& counts) {
  const Eigen::Vector3d outside = (b.lo - p).cwiseMax(p - b.hi);
  if ((outside.array() <= 0.0).all()) return -1.0;
  counts = std::abs(p.x()) >= b.between_jaws;
  return outside.cwiseMax(0.0).norm();
}

// The tool's bounding box in the base frame, grown by `grow`.
void baseBounds(const ToolVolume& tool, const Eigen::Isometry3d& T_base_grasp, double grow, Eigen::Vector3d& lo,
                Eigen::Vector3d& hi) {
  lo.setConstant(std::numeric_limits<double>::infinity());
  hi = -lo;
  const auto add = [&](const Eigen::Vector3d& local_lo, const Eigen::Vector3d& local_hi) {
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d local((corner & 1) ? local_hi.x() : local_lo.x(),
                                  (corner & 2) ? local_hi.y() : local_lo.y(),
                                  (corner & 4) ? local_hi.z() : local_lo.z());
      const Eigen::Vector3d base = T_base_grasp * local;
      lo = lo.cwiseMin(base);
      hi = hi.cwiseMax(base);
    }
  };
  for (int i = 0; i < tool.cylinder_count; ++i) {
    const Cylinder& c = tool.cylinders[static_cast<std::size_t>(i)];
    const double r = c.radius + grow;
    add({-r, -r, c.z_lo - grow}, {r, r, c.z_hi + grow});
  }
  for (int i = 0; i < tool.box_count; ++i) {
    const Box& b = tool.boxes[static_cast<std::size_t>(i)];
    add(b.lo.array() - grow, b.hi.array() + grow);
  }
  if (const auto& body = tool.bent_body) {
    // The swept axis is a parallelogram: its corners' box, grown by the radius.
    Eigen::Vector3d local_lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d local_hi = -local_lo;
    for (const double along : {0.0, body->length}) {
      for (const double back : {0.0, body->sweep}) {
        const Eigen::Vector3d corner = body->start + along * body->axis - back * Eigen::Vector3d::UnitZ();
        local_lo = local_lo.cwiseMin(corner);
        local_hi = local_hi.cwiseMax(corner);
      }
    }
    add(local_lo.array() - body->radius - grow, local_hi.array() + body->radius + grow);
  }
}

ToolVolume toolVolume(const GripperParams& gripper, const ToolSweep& sweep) {
  return gripper.type == GripperType::Suction ? suctionVolume(gripper, sweep) : parallelVolume(gripper, sweep);
}

}  // namespace binpick::picking
