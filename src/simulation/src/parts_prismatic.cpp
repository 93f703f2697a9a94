// The prismatic built-in parts: a profile drawn in millimetres (x, y), extruded along z.
#include <cmath>

#include "part_recipes.hpp"

namespace binpick::simulation::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Appends `steps` + 1 points (millimetres in, metres out) on a circular arc from angle a0 to a1.
void appendArc(std::vector<Eigen::Vector2d>& profile, const Eigen::Vector2d& centre, double radius, double a0,
               double a1, int steps) {
  for (int s = 0; s <= steps; ++s) {
    const double a = a0 + (a1 - a0) * s / steps;
    profile.push_back(1e-3 * (centre + radius * Eigen::Vector2d(std::cos(a), std::sin(a))));
  }
}

Eigen::Matrix3d rotationZ(double angle) {
  return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

Eigen::Matrix3d halfTurnX() { return Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX()).toRotationMatrix(); }

}  // namespace

// An L with unequal legs (80 mm along x, 50 mm along y, both 8 mm thick) extruded 30 mm. Unequal
// legs remove the mirror about the diagonal, so no half-turn maps it onto itself: identity only.
Part makeLBracket() {
  const auto profile = millimetres({{0, 0}, {80, 0}, {80, 8}, {8, 8}, {8, 50}, {0, 50}});
  return {"l_bracket", "L bracket, legs 80 x 50 mm, 8 mm thick, 30 mm wide",
          centredOnVolumeCentroid(makePrism(profile, 0.030)), Symmetry{}};
}

// A long, narrow L (legs 110 mm along x and 35 mm along y, both 6 mm thick) extruded 25 mm.
// Unequal legs: identity only, as for l_bracket.
Part makeLBracketLong() {
  const auto profile = millimetres({{0, 0}, {110, 0}, {110, 6}, {6, 6}, {6, 35}, {0, 35}});
  return {"l_bracket_long", "long L bracket, legs 110 x 35 mm, 6 mm thick, 25 mm wide",
          centredOnVolumeCentroid(makePrism(profile, 0.025)), Symmetry{}};
}

// A lever clamp: a 90 mm bar with a chamfered tip, a step up to a taller jaw and a notch in the
// jaw, extruded 20 mm. The profile has no mirror line and no rotational symmetry: identity only.
Part makeClamp() {
  const auto profile = millimetres({{0, 0},
                                    {90, 0},
                                    {90, 6},
                                    {86, 10},
                                    {55, 10},
                                    {55, 14},
                                    {20, 14},
                                    {20, 30},
                                    {12, 30},
                                    {12, 22},
                                    {6, 22},
                                    {6, 30},
                                    {0, 30}});
  return {"clamp", "lever clamp, 90 x 30 mm with a step and a jaw notch, 20 mm thick",
          centredOnVolumeCentroid(makePrism(profile, 0.020)), Symmetry{}};
}

// A spur gear: 12 trapezoid teeth (root radius 25 mm, tip radius 30 mm; 15 degrees wide at the
// root, 7.2 at the tip) on a 12 mm thick prism, tooth 0 centred on +x. Its symmetry is the
// dihedral group D12: the 12 turns about z by multiples of 30 degrees, and the same turns after
// the flip over (a half-turn about x, through tooth 0), i.e. the half-turns about the 12 in-plane
// axes through a tooth or a gap centre: 24 rotations.
Part makeGear() {
  constexpr int kTeeth = 12;
  constexpr double kRoot = 25.0, kTip = 30.0;
  const double pitch = 2.0 * kPi / kTeeth;
  const auto polar = [](double radius, double angle) {
    return Eigen::Vector2d(1e-3 * radius * std::cos(angle), 1e-3 * radius * std::sin(angle));
  };
  std::vector<Eigen::Vector2d> profile;
  for (int k = 0; k < kTeeth; ++k) {
    const double centre = k * pitch;
    profile.push_back(polar(kRoot, centre - 0.25 * pitch));
    profile.push_back(polar(kTip, centre - 0.12 * pitch));
    profile.push_back(polar(kTip, centre + 0.12 * pitch));
    profile.push_back(polar(kRoot, centre + 0.25 * pitch));
    profile.push_back(polar(kRoot, centre + 0.5 * pitch));  // the middle of the gap
  }
  Symmetry symmetry;
  symmetry.discrete.clear();
  for (int k = 0; k < kTeeth; ++k) symmetry.discrete.push_back(rotationZ(k * pitch));
  for (int k = 0; k < kTeeth; ++k) symmetry.discrete.push_back(rotationZ(k * pitch) * halfTurnX());
  symmetry.discrete.front() = Eigen::Matrix3d::Identity();  // exactly, not cos(0) etc.
  return {"gear", "spur gear, 12 trapezoid teeth, 60 mm outer diameter, 12 mm thick",
          centredOnVolumeCentroid(makePrism(profile, 0.012)), symmetry};
}

// A rocker-switch housing seen from the side: a 60 x 30 mm body with a rocker on top between
// x = 15 and 45 mm, tilted (12 mm high at the left end, 4 mm at the right), extruded 35 mm. The
// tilt breaks every mirror of the profile: identity only.
Part makeSwitch() {
  const auto profile = millimetres({{0, 0}, {60, 0}, {60, 30}, {45, 30}, {45, 34}, {15, 42}, {15, 30}, {0, 30}});
  return {"switch", "rocker switch housing, 60 x 30 mm body with a tilted rocker, 35 mm deep",
          centredOnVolumeCentroid(makePrism(profile, 0.035)), Symmetry{}};
}

// A flat plate with a bulge: a 70 x 45 mm rectangle with 8 mm corner radii and a semicircular
// bulge (radius 12 mm) on one long side, centred 10 mm off the middle, extruded 15 mm. The
// off-centre bulge breaks every mirror of the profile: identity only.
Part makeBulge() {
  constexpr double kHalfX = 35.0, kHalfY = 22.5, kCorner = 8.0, kBulge = 12.0, kBulgeX = 10.0;
  const double x = kHalfX - kCorner, y = kHalfY - kCorner;
  std::vector<Eigen::Vector2d> profile;  // counter-clockwise from the bottom-right corner
  appendArc(profile, {x, -y}, kCorner, -0.5 * kPi, 0.0, 6);
  appendArc(profile, {x, y}, kCorner, 0.0, 0.5 * kPi, 6);
  appendArc(profile, {kBulgeX, kHalfY}, kBulge, 0.0, kPi, 24);
  appendArc(profile, {-x, y}, kCorner, 0.5 * kPi, kPi, 6);
  appendArc(profile, {-x, -y}, kCorner, kPi, 1.5 * kPi, 6);
  return {"bulge", "plate, 70 x 45 mm with an off-centre 12 mm radius bulge, 15 mm thick",
          centredOnVolumeCentroid(makePrism(profile, 0.015)), Symmetry{}};
}

}  // namespace binpick::simulation::detail
