#pragma once
// The robot's gripper as the planner, the grasp generator and the virtual cell's robot see it:
// a suction cup or a parallel-jaw gripper at the end of a cylindrical tool body. All metres.
//
// Grasp frame (picking.hpp): z is the approach direction, pointing into the part; the origin is
// the grasp point.
// - Suction: the cup's sealing disc (diameter cup_diameter) lies in the grasp frame's xy plane,
//   centred on the origin; the cup itself fills the cylinder of radius cup_diameter / 2 from
//   z = -cup_length to z = 0.
// - Parallel jaw: the jaws close along the grasp frame's x axis; the origin lies midway between
//   the two contact points. Each finger is a box finger_thickness along x (outside its contact
//   face), finger_width along y, reaching from z = -finger_depth / 2 to z = +finger_depth / 2 at
//   its tip; the fingers open to at most `stroke` between their contact faces.
// - The tool body: a cylinder of radius tool_radius on the approach axis, from where the cup (or
//   the fingers' root at z = -finger_depth / 2) ends, tool_length further back along -z.
// - A suction tool may have a bent nose (nose_angle_deg > 0): the cup's axis then meets the body's
//   at the back of the cup, the body running back along bodyAxis(), tilted from -z towards the
//   grasp frame's +x. The wrist turns the tool about the cup's axis, so the planner chooses where
//   the body leans: away from a wall the straight tool would meet.
// Plain data: thread-safe.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>

namespace binpick::picking {

enum class GripperType { Suction, Parallel };
GripperType gripperTypeFromName(const std::string& name);  // "suction" | "parallel"
std::string gripperTypeName(GripperType type);

struct GripperParams {
  GripperType type = GripperType::Suction;
  // Suction
  double cup_diameter = 0.006;     // metres: the disc that must seal on the part
  double cup_length = 0.025;       // metres: cup + bellows along the approach axis
  double seal_tolerance = 0.0008;  // metres: how far the surface under the cup may leave its plane
  // Degrees the approach may lean off the face's normal, the bellows taking it up, where the
  // straight approach would bring the tool against a bin wall (0: never lean).
  double max_lean_deg = 6.0;
  // Degrees between the cup's axis and the tool body's (0: a straight tool). Industrial angled
  // nozzles come at 15-45 degrees.
  double nose_angle_deg = 0.0;
  // Parallel jaw
  double stroke = 0.080;            // metres: widest opening between the contact faces
  double finger_width = 0.012;      // metres, across the closing direction
  double finger_depth = 0.020;      // metres, along the approach
  double finger_thickness = 0.008;  // metres, along the closing direction
  // Tool body behind the cup or the fingers
  double tool_radius = 0.015;  // metres
  double tool_length = 0.15;   // metres
  void validate() const;       // throws core::Error naming the field
  // Parallel jaw: the opening between the contact faces when `requested` is asked for: at most
  // the stroke, the whole stroke when requested <= 0 (the part's width unknown).
  double jawOpening(double requested) const { return requested > 0.0 ? std::min(requested, stroke) : stroke; }
  // Metres from the grasp point back along the approach to the end of the tool body.
  double toolBack() const { return (type == GripperType::Suction ? cup_length : 0.5 * finger_depth) + tool_length; }
  // Whether the body leaves the cup's axis (a suction tool with a bent nose).
  bool bent() const { return type == GripperType::Suction && nose_angle_deg > 0.0; }
  // Grasp frame: the unit direction from the back of the cup (or the fingers' root) along the
  // body to its end; -z for a straight tool.
  Eigen::Vector3d bodyAxis() const {
    const double nose = bent() ? nose_angle_deg * M_PI / 180.0 : 0.0;
    return {std::sin(nose), 0.0, -std::cos(nose)};
  }
  // Grasp frame: where the body starts, on the approach axis behind the cup or the fingers, and
  // where it ends.
  Eigen::Vector3d bodyStart() const {
    return {0.0, 0.0, -(type == GripperType::Suction ? cup_length : 0.5 * finger_depth)};
  }
  Eigen::Vector3d bodyEnd() const { return bodyStart() + tool_length * bodyAxis(); }
};

}  // namespace binpick::picking
