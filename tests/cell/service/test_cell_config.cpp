// binpickd's settings file: the documented example parses, every mistake names its key.
#include <gtest/gtest.h>

#include <fstream>

#include "binpick/cell/cell_config.hpp"
#include "cell_scene.hpp"
#include "temp_directory_test.hpp"
#include "thrown_message.hpp"

namespace binpick::cell {
namespace {

using test::throwsNaming;
using testing::cellConfigYaml;
using testing::cellScene;

CellConfig parse(const std::string& yaml) { return parseCellConfig(yaml, "cell.yaml", "/base"); }

const std::string kMinimal =
    "source: {replay: {path: captures}}\n"
    "recipes: [{name: part, model: part.ply, grasps: [{translation: [0, 0, 0.01]}]}]\n";

TEST(CellConfig, TheDocumentedExampleParsesWithItsDefaults) {
  const CellConfig config = loadCellConfig(std::string(BINPICK_CONFIG_DIR) + "/binpickd.yaml");
  EXPECT_EQ(config.source.mode, SourceConfig::Mode::Replay);
  ASSERT_EQ(config.recipes.size(), 1u);
  EXPECT_EQ(config.recipes[0].grasps.size(), 2u);
  EXPECT_EQ(config.robot.port, 50100);
  EXPECT_EQ(config.robot.codec.max_line_length, 80u);
  EXPECT_FALSE(config.artefacts.has_value());  // directory "" saves nothing
  EXPECT_FALSE(config.limits.trim_memory_after_cycle);
  EXPECT_TRUE(parse(kMinimal + "limits: {trim_memory_after_cycle: true}\n").limits.trim_memory_after_cycle);
  ASSERT_TRUE(config.T_base_camera.has_value());
  // Looking straight down: the camera's z axis is the base's -z.
  EXPECT_NEAR((config.T_base_camera->linear() * Eigen::Vector3d::UnitZ()).z(), -1.0, 1e-12);
  EXPECT_NEAR(config.T_base_camera->translation().z(), 0.9, 1e-12);
}

TEST(CellConfig, PickingReadsEveryGripperKeyAndTheRankingWeights) {
  const CellConfig config = parse(kMinimal +
                                  "picking:\n"
                                  "  gripper: {type: parallel, cup_diameter: 0.02, cup_length: 0.03,\n"
                                  "            seal_tolerance: 0.001, stroke: 0.06, finger_width: 0.01,\n"
                                  "            finger_depth: 0.025, finger_thickness: 0.006,\n"
                                  "            tool_radius: 0.03, tool_length: 0.2}\n"
                                  "  ranking: {free: 3, height: 0.5, coverage: 2, upright: 0.25,\n"
                                  "            clearance: 0, quality: 4}\n"
                                  "  collision_margin: 0.003\n"
                                  "  finger_clearance: 0.004\n"
                                  "  clearance_cap: 0.03\n"
                                  "  cover_radius: 0.05\n"
                                  "  cover_height: 0.006\n"
                                  "  order: highest_first\n");
  const picking::PickParams& p = config.picking;
  const picking::GripperParams& g = p.gripper;
  EXPECT_EQ(g.type, picking::GripperType::Parallel);
  EXPECT_EQ(std::vector<double>({g.cup_diameter, g.cup_length, g.seal_tolerance, g.stroke, g.finger_width,
                                 g.finger_depth, g.finger_thickness, g.tool_radius, g.tool_length}),
            std::vector<double>({0.02, 0.03, 0.001, 0.06, 0.01, 0.025, 0.006, 0.03, 0.2}));
  const picking::RankWeights& w = p.ranking;
  EXPECT_EQ(std::vector<double>({w.free, w.height, w.coverage, w.upright, w.clearance, w.quality}),
            std::vector<double>({3, 0.5, 2, 0.25, 0, 4}));
  EXPECT_EQ(
      std::vector<double>({p.collision_margin, p.finger_clearance, p.clearance_cap, p.cover_radius, p.cover_height}),
      std::vector<double>({0.003, 0.004, 0.03, 0.05, 0.006}));
  EXPECT_EQ(p.order, picking::PickOrder::HighestFirst);
  EXPECT_EQ(parse(kMinimal).picking.order, picking::PickOrder::BestRank);  // absent: the ranking decides
  EXPECT_EQ(loadCellConfig(std::string(BINPICK_CONFIG_DIR) + "/binpickd.yaml").picking.order,
            picking::PickOrder::BestRank);
}

TEST(CellConfig, RobotConnectionSettingsAreRead) {
  const robot::RobotServerParams defaults;
  const robot::RobotServerParams example = loadCellConfig(std::string(BINPICK_CONFIG_DIR) + "/binpickd.yaml").robot;
  EXPECT_EQ(example.idle_timeout_ms, defaults.idle_timeout_ms);
  EXPECT_EQ(example.keepalive_idle_s, defaults.keepalive_idle_s);
  EXPECT_EQ(example.keepalive_interval_s, defaults.keepalive_interval_s);
  EXPECT_EQ(example.keepalive_count, defaults.keepalive_count);
  EXPECT_EQ(example.bad_request_log_interval_ms, defaults.bad_request_log_interval_ms);
  const robot::RobotServerParams read = parse(kMinimal +
                                              "robot: {idle_timeout_ms: 0, keepalive_idle_s: 5, "
                                              "keepalive_interval_s: 2, keepalive_count: 4, "
                                              "bad_request_log_interval_ms: 1000}\n")
                                            .robot;
  EXPECT_EQ(read.idle_timeout_ms, 0);
  EXPECT_EQ(read.keepalive_idle_s, 5);
  EXPECT_EQ(read.keepalive_interval_s, 2);
  EXPECT_EQ(read.keepalive_count, 4);
  EXPECT_EQ(read.bad_request_log_interval_ms, 1000);
}

TEST(CellConfig, RelativePathsAreRelativeToTheFile) {
  const CellConfig config = parse(kMinimal);
  EXPECT_EQ(config.source.replay.path, "/base/captures");
  EXPECT_EQ(config.recipes[0].model_file, "/base/part.ply");
  EXPECT_TRUE(config.source.replay.loop);  // the daemon replays forever by default
  EXPECT_FALSE(config.T_base_camera.has_value());
}

TEST(CellConfig, GraspRotationsFollowTheNamedConvention) {
  const CellConfig config = parse(
      "source: {replay: {path: c}}\n"
      "recipes: [{name: p, model: m.ply, grasps: [{translation: [0.01, 0, 0], rotation: [0, 90, 0], "
      "convention: euler_xyz}]}]\n");
  const Eigen::Isometry3d& grasp = config.recipes[0].grasps[0].T_model_grasp;
  // Ry(90): the approach (z) along the model's +x.
  EXPECT_NEAR((grasp.linear() * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitX()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(grasp.translation().x(), 0.01, 1e-12);
}

TEST(CellConfig, SymmetryOrderGivesTheRotations) {
  const CellConfig config = parse(
      "source: {replay: {path: c}}\n"
      "recipes: [{name: p, model: m.ply, symmetry: {order: 4, axis: [0, 0, 2]}, grasps: [{translation: [0, 0, 0]}]},\n"
      "          {name: q, model: m.ply, symmetry: {continuous: true, axis: [1, 0, 0]}, grasps: [{translation: [0, 0, "
      "0]}]}]\n");
  ASSERT_TRUE(config.recipes[0].symmetry.has_value());
  ASSERT_EQ(config.recipes[0].symmetry->discrete.size(), 4u);
  const Eigen::Vector3d turned = config.recipes[0].symmetry->discrete[1] * Eigen::Vector3d::UnitX();
  EXPECT_NEAR((turned - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-12);
  ASSERT_TRUE(config.recipes[1].symmetry.has_value());
  ASSERT_TRUE(config.recipes[1].symmetry->continuous_axis.has_value());
  EXPECT_NEAR(config.recipes[1].symmetry->continuous_axis->x(), 1.0, 1e-12);
}

TEST(CellConfig, MistakesNameTheKey) {
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "robot: {prot: 1}\n"); }, "robot.prot"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "robot: {port: many}\n"); }, "robot.port"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "robot: {port: 70000}\n"); }, "port"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "robot: {orientation: euler}\n"); }, "robot.orientation"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "robot: {framing: json}\n"); }, "robot.framing"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "limits: {capture_timeout_ms: 0}\n"); }, "capture_timeout_ms"));
  // The robot server's checks name the keys as the file spells them, under robot:.
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "robot: {allowed_clients: [\"300.1.1.1\"]}\n"); },
                           "robot.allowed_clients entry \"300.1.1.1\""));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "robot: {max_clients: 0}\n"); }, "robot.max_clients must be >= 1"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "robot: {bind_address: here}\n"); }, "robot.bind_address"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "robot: {max_line_length: 8}\n"); }, "robot.max_line_length"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "robot: {position_decimals: 12}\n"); }, "robot.position_decimals"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "robot: {idle_timeout_ms: -1}\n"); }, "robot.idle_timeout_ms must"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "robot: {keepalive_count: 0}\n"); }, "robot.keepalive_count must"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "picking: {order: random}\n"); }, "picking.order"));
  EXPECT_TRUE(
      throwsNaming([] { parse(kMinimal + "picking: {gripper: {tool_radius: -1}}\n"); }, "picking.gripper.tool_radius"));
  EXPECT_TRUE(
      throwsNaming([] { parse(kMinimal + "picking: {tool_radius: 0.02}\n"); }, "moved to picking.gripper.tool_radius"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "picking: {gripper: {type: magnet}}\n"); }, "picking.gripper.type"));
  EXPECT_TRUE(
      throwsNaming([] { parse(kMinimal + "picking: {gripper: {cup_size: 1}}\n"); }, "picking.gripper.cup_size"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "picking: {ranking: {free: -1}}\n"); }, "picking.ranking.free"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "reconstruction: {decode: {min_contrast: -1}}\n"); }, "min_contrast"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "hand_eye: {T_base_camera: {rotation: [0, 0, 0, 0]}}\n"); },
                           "hand_eye.T_base_camera.rotation"));
  EXPECT_TRUE(throwsNaming([] { parse("source: {mode: camera}\nrecipes: []\n"); }, "source.mode"));
  EXPECT_TRUE(throwsNaming([] { parse("source: {replay: {path: c}}\n"); }, "recipes"));
  EXPECT_TRUE(
      throwsNaming([] { parse("source: {replay: {path: c}}\nrecipes: [{name: p, model: m.ply, grasps: []}]\n"); },
                   "recipes[0].grasps"));
  EXPECT_TRUE(throwsNaming(
      [] {
        parse("source: {replay: {path: c}}\nrecipes: [{name: p, model: m.ply, grasps: [{translaton: [0, 0, 0]}]}]\n");
      },
      "recipes[0].grasps[0].translaton"));
  EXPECT_TRUE(throwsNaming(
      [] {
        parse(
            "source: {replay: {path: c}}\nrecipes: [{name: p, model: m.ply, grasps: [{}]}, "
            "{name: p, model: n.ply, grasps: [{}]}]\n");
      },
      "used twice"));
  EXPECT_TRUE(throwsNaming([] { parse("source: {mode: replay}\nrecipes: []\n"); }, "replay.path"));
  EXPECT_TRUE(throwsNaming([] { parse("robot: [1, 2\n"); }, "not valid YAML"));
  EXPECT_TRUE(throwsNaming([] { parse(""); }, "empty"));
}

// Settings whose NEXT reply cannot carry a pick would pass the start and answer every NEXT with
// bad_message: they are refused, naming the setting and what it must be.
TEST(CellConfig, ARobotLineTooShortForAPickIsRefusedNamingTheMinimum) {
  const std::string message = test::thrownMessage([] { parse(kMinimal + "robot: {max_line_length: 20}\n"); });
  const std::string expected = "cell.yaml: robot.max_line_length must be >= ";
  ASSERT_EQ(message.rfind(expected, 0), 0u) << message;
  EXPECT_NE(message.find("(got 20)"), std::string::npos) << message;

  for (const char* orientation : {"quaternion", "euler_zyx", "fixed_xyz", "rotation_vector", "euler_xyz"}) {
    const std::string robot = std::string("robot: {orientation: ") + orientation;
    EXPECT_NO_THROW(parse(kMinimal + robot + "}\n")) << "the default 80 characters carry a pick";
    const std::string refused = test::thrownMessage([&] { parse(kMinimal + robot + ", max_line_length: 16}\n"); });
    ASSERT_EQ(refused.rfind(expected, 0), 0u) << orientation << ": " << refused;
    const int minimum = std::stoi(refused.substr(expected.size()));
    EXPECT_NO_THROW(parse(kMinimal + robot + ", max_line_length: " + std::to_string(minimum) + "}\n")) << orientation;
    EXPECT_TRUE(throwsNaming(
        [&] { parse(kMinimal + robot + ", max_line_length: " + std::to_string(minimum - 1) + "}\n"); }, expected))
        << orientation;
  }
  // Binary: a scale at which a coordinate of 10 m overflows an int32 field.
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "robot: {framing: binary, position_scale: 1000000}\n"); },
                           "robot.position_scale must be <= 214748"));
  EXPECT_TRUE(throwsNaming(
      [] { parse(kMinimal + "robot: {framing: binary, orientation: euler_zyx, orientation_scale: 1.0e8}\n"); },
      "robot.orientation_scale must be <= "));
  EXPECT_NO_THROW(parse(kMinimal + "robot: {framing: binary, max_line_length: 16}\n"));  // lines are ASCII's
}

class CellConfigFile : public test::TempDirectoryTest {};

TEST_F(CellConfigFile, TheTestSceneSettingsParse) {
  const std::string path = pathOf("cell.yaml");
  std::ofstream(path) << cellConfigYaml(cellScene());
  const CellConfig config = loadCellConfig(path);
  EXPECT_EQ(config.recipes.size(), 2u);
  EXPECT_EQ(config.robot.port, 0);
  EXPECT_TRUE(throwsNaming([&] { loadCellConfig(pathOf("missing.yaml")); }, "missing.yaml"));
}

}  // namespace
}  // namespace binpick::cell

namespace binpick::cell {
namespace {

TEST(CellConfig, TheWebViewIsOffWithoutItsSectionAndLocalByDefault) {
  EXPECT_FALSE(parse(kMinimal).web.has_value());
  const CellConfig config = parse(kMinimal + "web: {}\n");
  ASSERT_TRUE(config.web.has_value());
  EXPECT_EQ(config.web->bind_address, "127.0.0.1");
  EXPECT_EQ(config.web->port, 8080);
  EXPECT_TRUE(config.web->allowed_clients.empty());
  const CellConfig set = parse(kMinimal +
                               "web: {bind_address: 0.0.0.0, port: 8081, allowed_clients: [10.0.0.0/8], "
                               "threads: 2, timeout_ms: 2000}\n");
  EXPECT_EQ(set.web->bind_address, "0.0.0.0");
  EXPECT_EQ(set.web->port, 8081);
  EXPECT_EQ(set.web->allowed_clients, std::vector<std::string>{"10.0.0.0/8"});
  EXPECT_EQ(set.web->threads, 2);
  EXPECT_EQ(set.web->timeout_ms, 2000);
}

TEST(CellConfig, WebViewMistakesNameTheirKey) {
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "web: {port: 70000}\n"); }, "web.port must be in [0, 65535]"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "web: {bind_address: localhost}\n"); }, "web.bind_address"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "web: {allowed_clients: [\"10.0.0.0/33\"]}\n"); },
                           "web.allowed_clients entry \"10.0.0.0/33\""));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "web: {threads: 0}\n"); }, "web.threads"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "web: {timeout_ms: 10}\n"); }, "web.timeout_ms"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "web: {port: [1]}\n"); }, "web.port"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "web: {colour: blue}\n"); }, "web.colour"));
  EXPECT_TRUE(throwsNaming([] { parse(kMinimal + "robot: {port: 8080}\nweb: {port: 8080}\n"); },
                           "web.port must be different from robot.port"));
}

}  // namespace
}  // namespace binpick::cell
