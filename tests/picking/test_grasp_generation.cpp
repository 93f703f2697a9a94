// Grasps generated from the part model: where a suction cup seals, where parallel jaws hold, one
// per symmetry class, ranked.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "binpick/picking/grasp_generation.hpp"
#include "binpick/simulation/parts.hpp"
#include "thrown_message.hpp"

namespace binpick::picking {
namespace {

using test::throwsNaming;

constexpr double kMm = 1e-3;

// An axis-aligned box centred on the origin, sizes in metres.
io::TriangleMesh makeBox(double x, double y, double z) {
  return simulation::makePrism({{-x / 2, -y / 2}, {x / 2, -y / 2}, {x / 2, y / 2}, {-x / 2, y / 2}}, z);
}

// A closed cylinder about z, centred on the origin.
io::TriangleMesh makeCylinder(double radius, double length, int segments) {
  return simulation::makeLathe({{0, -length / 2}, {radius, -length / 2}, {radius, length / 2}, {0, length / 2}},
                               segments);
}

Eigen::Vector3d approachOf(const Grasp& grasp) { return grasp.T_model_grasp.linear().col(2); }

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

// The box face (axis, sign) a suction grasp approaches, or -1 when it approaches none within 1 degree.
int faceOf(const Grasp& grasp) {
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign : {-1, 1}) {
      if (angleDeg(approachOf(grasp), -sign * Eigen::Vector3d::Unit(axis)) < 1.0) return 2 * axis + (sign > 0);
    }
  }
  return -1;
}

GraspGenerationParams defaults() { return GraspGenerationParams{}; }

// A 16 mm cup (0.8 mm seal tolerance) on a 25 mm tool: wide enough that edges, curvature and
// narrow faces decide where it seals.
GripperParams wideCup() {
  GripperParams gripper;
  gripper.cup_diameter = 0.016;
  gripper.seal_tolerance = 0.0008;
  gripper.tool_radius = 0.025;
  return gripper;
}

TEST(SuctionGrasps, EveryFaceOfABoxAwayFromItsEdges) {
  const Eigen::Vector3d size(0.060, 0.040, 0.030);
  const GripperParams gripper = wideCup();
  const std::vector<Grasp> grasps = generateGrasps(makeBox(size.x(), size.y(), size.z()), gripper, {}, defaults());
  std::set<int> faces;
  const double cup_radius = gripper.cup_diameter / 2;
  for (const Grasp& grasp : grasps) {
    const int face = faceOf(grasp);
    ASSERT_GE(face, 0) << grasp.name << ": the approach is along no face normal";
    faces.insert(face);
    const int axis = face / 2;
    const Eigen::Vector3d point = grasp.T_model_grasp.translation();
    EXPECT_NEAR(std::abs(point[axis]), size[axis] / 2, 0.1 * kMm) << grasp.name << ": not on its face";
    for (int other = 0; other < 3; ++other) {
      if (other == axis) continue;
      EXPECT_GE(size[other] / 2 - std::abs(point[other]), cup_radius - 0.1 * kMm)
          << grasp.name << ": the cup crosses an edge";
    }
    EXPECT_GE(grasp.quality, 0.0);
    EXPECT_LE(grasp.quality, 1.0);
  }
  EXPECT_EQ(faces.size(), 6u);
  for (std::size_t i = 1; i < grasps.size(); ++i) EXPECT_GE(grasps[i - 1].quality, grasps[i].quality);
  // The best grasp is where the seal margin is widest and the lever shortest: a large face's middle.
  ASSERT_FALSE(grasps.empty());
  EXPECT_EQ(faceOf(grasps[0]) / 2, 2);
  EXPECT_LT(grasps[0].T_model_grasp.translation().head<2>().norm(), 10 * kMm);
  EXPECT_NE(grasps[0].name.find("suction 1 (face "), std::string::npos) << grasps[0].name;
}

TEST(SuctionGrasps, TheSameForTheSameSeedAndSpreadForAnother) {
  const io::TriangleMesh box = makeBox(0.050, 0.040, 0.030);
  GraspGenerationParams params;
  const auto first = generateGrasps(box, GripperParams{}, {}, params);
  const auto again = generateGrasps(box, GripperParams{}, {}, params);
  ASSERT_EQ(first.size(), again.size());
  for (std::size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(first[i].name, again[i].name);
    EXPECT_TRUE(first[i].T_model_grasp.isApprox(again[i].T_model_grasp, 1e-12));
  }
}

TEST(SuctionGrasps, ACylinderSideOnlyWhenItsCurvatureLetsTheCupSeal) {
  // 16 mm cup, 0.8 mm tolerance of which 0.6 used: a side of radius >= 54 mm seals.
  const GripperParams gripper = wideCup();
  const auto sideAndEnds = [&](const io::TriangleMesh& mesh) {
    int side = 0, ends = 0;
    for (const Grasp& grasp : generateGrasps(mesh, gripper, {}, defaults())) {
      const Eigen::Vector3d approach = approachOf(grasp);
      if (std::abs(approach.z()) > std::cos(1.0 * M_PI / 180.0)) ++ends;
      if (std::abs(approach.z()) < 0.02) ++side;
    }
    return std::make_pair(side, ends);
  };
  const auto [thin_side, thin_ends] = sideAndEnds(makeCylinder(0.012, 0.040, 64));
  EXPECT_EQ(thin_side, 0);
  EXPECT_GE(thin_ends, 2);
  const auto [thick_side, thick_ends] = sideAndEnds(makeCylinder(0.060, 0.030, 96));
  EXPECT_GT(thick_side, 0);
  EXPECT_GE(thick_ends, 2);
}

// The default 6 mm cup on shafts: its rim sags 0.63 mm on one 15 mm across, within the 0.8 mm
// tolerance but not within what a grasp may use of it (0.6 mm), and 0.58 mm on one 16 mm across.
TEST(SuctionGrasps, AShaftSideOnlyWhereTheCupKeepsAReserveOfItsCompliance) {
  PartSymmetry revolved;
  revolved.continuous_axis = Eigen::Vector3d::UnitZ();
  const auto sides = [&](double diameter, double seal_reserve) {
    GraspGenerationParams params;
    params.seal_reserve = seal_reserve;
    const auto grasps = generateGrasps(makeCylinder(diameter / 2, 0.080, 96), GripperParams{}, revolved, params);
    return std::count_if(grasps.begin(), grasps.end(),
                         [](const Grasp& grasp) { return std::abs(approachOf(grasp).z()) < 0.02; });
  };
  EXPECT_EQ(sides(0.015, defaults().seal_reserve), 0);
  EXPECT_GT(sides(0.015, 0.0), 0);
  EXPECT_GT(sides(0.016, defaults().seal_reserve), 0);
}

// A block with a slot 7 mm wide and 5 mm deep along its top: a 6 mm cup fits the slot's floor
// with 0.5 mm each side, and keeps out of it once it wants 1 mm of room from the walls (the tool's
// clearance, which would keep it out as well, left out).
TEST(SuctionGrasps, NotInAGrooveBarelyWiderThanTheCup) {
  const io::TriangleMesh slotted = simulation::makePrism({{-0.015, 0.0},
                                                          {0.015, 0.0},
                                                          {0.015, 0.020},
                                                          {0.0035, 0.020},
                                                          {0.0035, 0.015},
                                                          {-0.0035, 0.015},
                                                          {-0.0035, 0.020},
                                                          {-0.015, 0.020}},
                                                         0.020);
  const auto inTheSlot = [&](double cup_clearance) {
    GraspGenerationParams params;
    params.cup_clearance = cup_clearance;
    params.tool_clearance = 0.0;
    params.sample_spacing = 0.001;  // the cup fits only within 0.5 mm of the slot's middle
    const auto grasps = generateGrasps(slotted, GripperParams{}, PartSymmetry{}, params);
    return std::count_if(grasps.begin(), grasps.end(), [](const Grasp& grasp) {
      return approachOf(grasp).y() < -0.99 && grasp.T_model_grasp.translation().y() < 0.0155;
    });
  };
  EXPECT_GT(inTheSlot(0.0), 0);
  EXPECT_EQ(inTheSlot(defaults().cup_clearance), 0);
}

// A flanged hub (flange 56 x 6 mm, hub 24 mm across standing 16 mm on it): a cup on the hub's
// side keeps its rim tool_clearance from the flange, where the planner, growing the tool by its
// collision margin against the measured flange, would refuse it at every pick.
TEST(SuctionGrasps, OnAHubsSideClearOfItsFlangeByTheToolClearance) {
  const io::TriangleMesh hub = simulation::makeLathe(
      {{0, 0}, {28 * kMm, 0}, {28 * kMm, 6 * kMm}, {12 * kMm, 6 * kMm}, {12 * kMm, 22 * kMm}, {0, 22 * kMm}}, 48);
  PartSymmetry revolved;
  revolved.continuous_axis = Eigen::Vector3d::UnitZ();
  const auto lowestOnTheSide = [&](double tool_clearance) {
    GraspGenerationParams params = defaults();
    params.tool_clearance = tool_clearance;
    double lowest = std::numeric_limits<double>::infinity();
    for (const Grasp& grasp : generateGrasps(hub, GripperParams{}, revolved, params)) {
      if (std::abs(approachOf(grasp).z()) < 0.02) lowest = std::min(lowest, grasp.T_model_grasp.translation().z());
    }
    return lowest;
  };
  const double cup_radius = 0.5 * GripperParams{}.cup_diameter;
  const double kept = lowestOnTheSide(defaults().tool_clearance);
  ASSERT_TRUE(std::isfinite(kept)) << "no grasp on the hub's side";
  EXPECT_GE(kept - cup_radius - 6 * kMm, defaults().tool_clearance - 0.1 * kMm);
  EXPECT_LT(lowestOnTheSide(0.0) - cup_radius - 6 * kMm, defaults().tool_clearance - 1 * kMm);
}

TEST(SuctionGrasps, ASymmetricPartKeepsOneGraspPerClass) {
  const io::TriangleMesh box = makeBox(0.040, 0.040, 0.020);
  PartSymmetry four_fold;
  for (int k = 1; k < 4; ++k)
    four_fold.discrete.push_back(Eigen::AngleAxisd(k * M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix());
  GraspGenerationParams params;
  params.max_grasps = 1000;
  const auto plain = generateGrasps(box, GripperParams{}, {}, params);
  const auto symmetric = generateGrasps(box, GripperParams{}, four_fold, params);
  ASSERT_FALSE(symmetric.empty());
  EXPECT_LT(symmetric.size(), plain.size());
  for (std::size_t i = 0; i < symmetric.size(); ++i) {
    for (std::size_t j = i + 1; j < symmetric.size(); ++j) {
      for (const Eigen::Matrix3d& S : four_fold.discrete) {
        const Eigen::Vector3d moved_point = S * symmetric[i].T_model_grasp.translation();
        const bool same_place =
            (moved_point - symmetric[j].T_model_grasp.translation()).norm() <= params.min_separation;
        const bool same_approach =
            angleDeg(S * approachOf(symmetric[i]), approachOf(symmetric[j])) <= params.symmetry_angle_deg;
        EXPECT_FALSE(same_place && same_approach) << symmetric[i].name << " and " << symmetric[j].name;
      }
    }
  }
  // Still both ends and a side.
  std::set<int> faces;
  for (const Grasp& grasp : symmetric) faces.insert(faceOf(grasp));
  EXPECT_TRUE(faces.count(4) && faces.count(5)) << "an end of the box has no grasp";
  EXPECT_GE(faces.size(), 3u);
}

TEST(SuctionGrasps, ATurnedPartWithAContinuousAxisKeepsOneGraspPerHeight) {
  PartSymmetry turned;
  turned.continuous_axis = Eigen::Vector3d::UnitZ();
  GraspGenerationParams params;
  params.max_grasps = 1000;
  const auto grasps = generateGrasps(makeCylinder(0.060, 0.030, 96), wideCup(), turned, params);
  int side = 0;
  for (const Grasp& grasp : grasps) side += std::abs(approachOf(grasp).z()) < 0.02;
  EXPECT_GE(side, 1);
  // The side is 30 mm high, the cup 16 mm: the cup's centre has 14 mm to move in, 10 mm apart.
  EXPECT_LE(side, 2);
}

TEST(SuctionGrasps, AModelGivenAsACloudWithNormals) {
  const Eigen::Vector3d size(0.060, 0.040, 0.030);
  io::PointCloud cloud;
  const double step = 0.001;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int sign : {-1, 1}) {
      for (double a = -size[u] / 2 + step / 2; a < size[u] / 2; a += step) {
        for (double b = -size[v] / 2 + step / 2; b < size[v] / 2; b += step) {
          Eigen::Vector3d point, normal = Eigen::Vector3d::Zero();
          point[axis] = sign * size[axis] / 2;
          point[u] = a;
          point[v] = b;
          normal[axis] = sign;
          cloud.points.push_back(point.cast<float>());
          cloud.normals.push_back(normal.cast<float>());
        }
      }
    }
  }
  std::set<int> faces;
  for (const Grasp& grasp : generateGrasps(cloud, GripperParams{}, {}, defaults())) {
    faces.insert(faceOf(grasp));
    const int axis = faceOf(grasp) / 2;
    ASSERT_GE(axis, 0);
    EXPECT_NEAR(std::abs(grasp.T_model_grasp.translation()[axis]), size[axis] / 2, 0.1 * kMm);
  }
  EXPECT_EQ(faces.size(), 6u);
  cloud.normals.clear();
  EXPECT_TRUE(throwsNaming([&] { generateGrasps(cloud, GripperParams{}, {}, defaults()); }, "normals"));
}

GripperParams parallelJaws(double stroke) {
  GripperParams gripper;
  gripper.type = GripperType::Parallel;
  gripper.stroke = stroke;
  gripper.tool_radius = 0.015;
  return gripper;
}

TEST(ParallelGrasps, OppositeFacesOfABoxNarrowerThanTheStroke) {
  const Eigen::Vector3d size(0.030, 0.060, 0.020);
  const auto grasps = generateGrasps(makeBox(size.x(), size.y(), size.z()), parallelJaws(0.050), {}, defaults());
  ASSERT_FALSE(grasps.empty());
  std::set<int> closing_axes;
  for (const Grasp& grasp : grasps) {
    const Eigen::Matrix3d R = grasp.T_model_grasp.linear();
    EXPECT_NEAR(std::abs(R.col(0).dot(R.col(2))), 0.0, 1e-9) << "the approach must be across the closing";
    int axis = 0;
    R.col(0).cwiseAbs().maxCoeff(&axis);
    EXPECT_LT(angleDeg(R.col(0).cwiseAbs(), Eigen::Vector3d::Unit(axis)), 1.0) << grasp.name;
    EXPECT_LE(size[axis], 0.050) << grasp.name << ": wider than the stroke";
    closing_axes.insert(axis);
    // Both contacts on the opposite faces: the grasp point midway.
    const Eigen::Vector3d centre = grasp.T_model_grasp.translation();
    const Eigen::Vector3d contact_a = centre + size[axis] / 2 * R.col(0),
                          contact_b = centre - size[axis] / 2 * R.col(0);
    EXPECT_NEAR(std::abs(contact_a[axis]), size[axis] / 2, 0.1 * kMm) << grasp.name;
    EXPECT_NEAR(contact_a[axis], -contact_b[axis], 0.1 * kMm) << grasp.name;
    EXPECT_NE(grasp.name.find("parallel"), std::string::npos);
  }
  EXPECT_EQ(closing_axes, (std::set<int>{0, 2}));  // 30 and 20 mm; the 60 mm is beyond the 50 mm stroke
}

TEST(ParallelGrasps, NoneWhenThePartIsWiderThanTheStroke) {
  EXPECT_TRUE(generateGrasps(makeBox(0.100, 0.090, 0.085), parallelJaws(0.080), {}, defaults()).empty());
}

// The grasps whose jaws close across the part's axis z with the approach `along_axis` or across it.
std::vector<Grasp> acrossTheAxis(const std::vector<Grasp>& grasps, bool approach_along_axis) {
  std::vector<Grasp> across;
  for (const Grasp& grasp : grasps) {
    const Eigen::Matrix3d R = grasp.T_model_grasp.linear();
    const bool along = std::abs(R.col(2).z()) > std::cos(1.0 * M_PI / 180.0);
    const bool perpendicular = std::abs(R.col(2).z()) < 0.02;
    if (std::abs(R.col(0).z()) < 0.02 && (approach_along_axis ? along : perpendicular)) across.push_back(grasp);
  }
  return across;
}

// A ring or a gear lying on its face is held across its whole diameter from above (the far jaw
// on the outermost surface, past the bore), its rim touching each finger along a line; the closing
// line runs through the axis, or beside it on a gear's flat tooth tip (3.8 mm wide).
TEST(ParallelGrasps, ARingAndAGearAcrossTheirDiameterFromAlongTheAxis) {
  for (const auto& [name, diameter] : {std::pair{"ring_magnet", 0.050}, std::pair{"gear", 0.060}}) {
    const simulation::Part part = simulation::makePart(name);
    const auto grasps = acrossTheAxis(generateGrasps(part.mesh, parallelJaws(0.080), part.symmetry, defaults()), true);
    const bool across_diameter = std::any_of(grasps.begin(), grasps.end(), [&](const Grasp& grasp) {
      return std::abs(grasp.width - diameter) < 0.5 * kMm && grasp.T_model_grasp.translation().head<2>().norm() < 2e-3;
    });
    EXPECT_TRUE(across_diameter) << name << ": no grasp across the " << diameter * 1e3 << " mm diameter";
  }
}

// Lying on the floor, a gear or a ring is held across its rim above its lower edge: the fingertips
// stop 2.5 mm short of the face it lies on, so that they stay clear of the floor.
TEST(ParallelGrasps, FingertipsStopShortOfTheFaceThePartLiesOn) {
  for (const char* name : {"ring_magnet", "gear"}) {
    const simulation::Part part = simulation::makePart(name);
    const GripperParams jaws = parallelJaws(0.080);
    const auto grasps = acrossTheAxis(generateGrasps(part.mesh, jaws, part.symmetry, defaults()), true);
    ASSERT_FALSE(grasps.empty()) << name;
    for (const Grasp& grasp : grasps) {
      const Eigen::Vector3d approach = approachOf(grasp);
      const Eigen::Vector3d tip = grasp.T_model_grasp * Eigen::Vector3d(0, 0, 0.5 * jaws.finger_depth);
      double far_side = -1.0;
      for (const Eigen::Vector3f& vertex : part.mesh.vertices)
        far_side = std::max(far_side, vertex.cast<double>().dot(approach));
      EXPECT_LE(tip.dot(approach), far_side - 0.0025 + 1e-9) << name << ", " << grasp.name;
    }
  }
}

// A slender shaft (10 mm across, lying as it will in a bin) is held across its body from beside its
// axis: flat fingers touch it along a line, and the contact lies 2 mm from the fingertips so that
// they stop above whatever the shaft lies on.
TEST(ParallelGrasps, AShaftAcrossItsBodyNearTheFingertips) {
  const io::TriangleMesh shaft = makeCylinder(0.005, 0.090, 48);
  PartSymmetry revolved;
  revolved.continuous_axis = Eigen::Vector3d::UnitZ();
  const GripperParams jaws = parallelJaws(0.080);
  const auto grasps = acrossTheAxis(generateGrasps(shaft, jaws, revolved, defaults()), false);
  ASSERT_FALSE(grasps.empty());
  for (const Grasp& grasp : grasps) {
    EXPECT_NEAR(grasp.width, 0.010, 0.1 * kMm) << grasp.name;
    EXPECT_NE(grasp.name.find("on lines"), std::string::npos) << grasp.name;
    const Eigen::Vector3d tip = grasp.T_model_grasp * Eigen::Vector3d(0, 0, 0.5 * jaws.finger_depth);
    // The contacts lie on opposite facets, their line up to half a facet (0.33 mm) off the axis.
    const double past_axis = tip.head<2>().dot(approachOf(grasp).head<2>());
    EXPECT_NEAR(past_axis, 0.002, 0.4 * kMm) << grasp.name << ": how far the fingertips reach past the contact";
  }
}

// A flange 6 mm thick is held across its 56 mm diameter from along its axis, its rim touching each
// finger along a line over the flange's whole thickness (a flanged hub resting on its hub end, the
// flange up, offers nothing else from above).
TEST(ParallelGrasps, AThinFlangeAcrossItsDiameterOverItsWholeThickness) {
  const io::TriangleMesh flange = makeCylinder(0.028, 0.006, 48);
  PartSymmetry revolved;
  revolved.continuous_axis = Eigen::Vector3d::UnitZ();
  const auto grasps = acrossTheAxis(generateGrasps(flange, parallelJaws(0.080), revolved, defaults()), true);
  const bool across_diameter = std::any_of(grasps.begin(), grasps.end(), [](const Grasp& grasp) {
    return std::abs(grasp.width - 0.056) < 0.5 * kMm && grasp.name.find("on lines") != std::string::npos;
  });
  EXPECT_TRUE(across_diameter) << grasps.size() << " grasps across the axis from along it, none across the diameter";
}

TEST(GraspGenerationParams, BadValuesThrowNamingTheField) {
  const io::TriangleMesh box = makeBox(0.05, 0.05, 0.05);
  GraspGenerationParams params;
  params.sample_spacing = 0.0;
  EXPECT_TRUE(throwsNaming([&] { generateGrasps(box, GripperParams{}, {}, params); }, "sample_spacing"));
  params = {};
  params.max_grasps = 0;
  EXPECT_TRUE(throwsNaming([&] { params.validate(); }, "max_grasps"));
  params = {};
  params.margin_weight = 1.5;
  EXPECT_TRUE(throwsNaming([&] { params.validate(); }, "margin_weight"));
  params = {};
  params.seal_reserve = 1.0;
  EXPECT_TRUE(throwsNaming([&] { params.validate(); }, "seal_reserve"));
  params = defaults();
  params.cup_clearance = -0.001;
  EXPECT_TRUE(throwsNaming([&] { params.validate(); }, "cup_clearance"));
  params = defaults();
  params.tool_clearance = std::nan("");
  EXPECT_TRUE(throwsNaming([&] { params.validate(); }, "tool_clearance"));
  params = {};
  params.approach_directions = 0;
  EXPECT_TRUE(throwsNaming([&] { params.validate(); }, "approach_directions"));
  GripperParams gripper;
  gripper.cup_diameter = -1;
  EXPECT_TRUE(throwsNaming([&] { generateGrasps(box, gripper, {}, {}); }, "cup_diameter"));
  PartSymmetry mirror;
  mirror.discrete.push_back(Eigen::Vector3d(1, 1, -1).asDiagonal());
  EXPECT_TRUE(throwsNaming([&] { generateGrasps(box, GripperParams{}, mirror, {}); }, "symmetry"));
  EXPECT_TRUE(throwsNaming([&] { generateGrasps(io::TriangleMesh{}, GripperParams{}, {}, {}); }, "model"));
}

struct Plane {
  Eigen::Vector3d normal;
  double offset = 0.0;  // normal . x on the plane
  double area = 0.0;
};

// The mesh's planar faces: triangles grouped by normal (1 degree) and offset (0.1 mm).
std::vector<Plane> planesOf(const io::TriangleMesh& mesh) {
  std::vector<Plane> planes;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>(), b = mesh.vertices[t[1]].cast<double>(),
                          c = mesh.vertices[t[2]].cast<double>();
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    const Eigen::Vector3d normal = cross.normalized();
    auto same = std::find_if(planes.begin(), planes.end(), [&](const Plane& plane) {
      return angleDeg(plane.normal, normal) < 1.0 && std::abs(plane.offset - normal.dot(a)) < 0.1 * kMm;
    });
    if (same == planes.end()) same = planes.insert(planes.end(), Plane{normal, normal.dot(a), 0.0});
    same->area += 0.5 * cross.norm();
  }
  return planes;
}

// Every built-in part: suction grasps on each large planar face (300 mm^2 or more), with a cup
// small enough for the thinnest walls (6 mm) on a slim tool (a wide one hits the part in front of
// some faces, e.g. the clamp's bar before its jaw), the face given by a grasp or a symmetric copy.
TEST(SuctionGrasps, EveryBuiltInPartOnEachLargeFace) {
  GripperParams small_cup;
  small_cup.cup_diameter = 0.005;
  small_cup.tool_radius = 0.003;
  GraspGenerationParams params;
  params.max_grasps = 200;
  for (const std::string& name : simulation::partNames()) {
    const simulation::Part part = simulation::makePart(name);
    PartSymmetry symmetry;
    symmetry.discrete = part.symmetry.discrete;
    symmetry.continuous_axis = part.symmetry.continuous_axis;
    const auto grasps = generateGrasps(part.mesh, small_cup, symmetry, params);
    int large_faces = 0;
    for (const Plane& plane : planesOf(part.mesh)) {
      if (plane.area < 300e-6) continue;
      ++large_faces;
      const bool held = std::any_of(grasps.begin(), grasps.end(), [&](const Grasp& grasp) {
        return std::any_of(symmetry.discrete.begin(), symmetry.discrete.end(), [&](const Eigen::Matrix3d& S) {
          const double off_plane = plane.normal.dot(S * grasp.T_model_grasp.translation()) - plane.offset;
          return angleDeg(S * approachOf(grasp), -plane.normal) < 1.0 && std::abs(off_plane) < 0.1 * kMm;
        });
      });
      EXPECT_TRUE(held) << name << ": no grasp on the face with normal " << plane.normal.transpose();
    }
    EXPECT_GE(large_faces, 2) << name;
  }
}

// With a 16 mm cup: the ring magnet (13 mm between bore and rim, a 25 mm radius side)
// has nowhere to seal; the plate with a bulge seals on both its sides.
TEST(SuctionGrasps, ABuiltInPartTooNarrowForTheCupHasNone) {
  EXPECT_TRUE(generateGrasps(simulation::makePart("ring_magnet").mesh, wideCup(), {}, defaults()).empty());
  int sides = 0;
  for (const Grasp& grasp : generateGrasps(simulation::makePart("bulge").mesh, wideCup(), {}, defaults())) {
    sides += std::abs(approachOf(grasp).z()) > std::cos(1.0 * M_PI / 180.0);
  }
  EXPECT_GE(sides, 2);
}

}  // namespace
}  // namespace binpick::picking
