// A recipe's grasps: written in place, read from a grasps file, or generated from the model.
#include <gtest/gtest.h>

#include <fstream>

#include "binpick/cell/cell_config.hpp"
#include "binpick/cell/cell_setup.hpp"
#include "binpick/cell/grasps_file.hpp"
#include "binpick/io/geometry_io.hpp"
#include "binpick/simulation/parts.hpp"
#include "temp_directory_test.hpp"
#include "thrown_message.hpp"

namespace binpick::cell {
namespace {

using test::throwsNaming;

class RecipeGrasps : public test::TempDirectoryTest {
 protected:
  // `more`: further top-level settings, one or more lines.
  CellConfig parse(const std::string& recipe, const std::string& more = "") {
    return parseCellConfig("source: {replay: {path: captures}}\nrecipes: [" + recipe + "]\n" + more, "cell.yaml",
                           root());
  }
};

std::vector<picking::Grasp> someGrasps() {
  picking::Grasp top{"suction 1 (face +z)", Eigen::Isometry3d::Identity(), 0.875};
  top.T_model_grasp.translation() = Eigen::Vector3d(0.001, -0.002, 0.015);
  top.T_model_grasp.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  picking::Grasp side{"suction 2 (face \"-y\")", Eigen::Isometry3d::Identity(), 0.25};
  side.T_model_grasp.translation() = Eigen::Vector3d(0.02, -0.0125, 0);
  side.T_model_grasp.linear() = Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  return {top, side};
}

TEST_F(RecipeGrasps, AGraspsFileRoundTripsThroughTheRecipeReader) {
  const std::vector<picking::Grasp> written = someGrasps();
  writeGraspsFile(pathOf("part.grasps.yaml"), written, "generated for a test\nsecond line");
  const CellConfig config = parse("{name: part, model: part.ply, grasps: part.grasps.yaml}");
  const std::vector<picking::Grasp>& read = config.recipes[0].grasps;
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].name, written[i].name);
    EXPECT_NEAR(read[i].quality, written[i].quality, 1e-9);
    EXPECT_NEAR((read[i].T_model_grasp.translation() - written[i].T_model_grasp.translation()).norm(), 0.0, 1e-9);
    EXPECT_TRUE(read[i].T_model_grasp.linear().isApprox(written[i].T_model_grasp.linear(), 1e-9));
  }
}

TEST_F(RecipeGrasps, QualityIsReadInPlaceAndChecked) {
  const CellConfig config = parse("{name: p, model: m.ply, grasps: [{translation: [0, 0, 0], quality: 0.5}]}");
  EXPECT_DOUBLE_EQ(config.recipes[0].grasps[0].quality, 0.5);
  EXPECT_TRUE(throwsNaming([&] { parse("{name: p, model: m.ply, grasps: [{quality: 2}]}"); }, "grasps[0].quality"));
}

TEST_F(RecipeGrasps, AMissingOrBrokenGraspsFileNamesTheRecipeAndTheFile) {
  EXPECT_TRUE(throwsNaming([&] { parse("{name: p, model: m.ply, grasps: none.yaml}"); }, "recipes[0].grasps"));
  std::ofstream(pathOf("bad.yaml")) << "grasps:\n  - {name: a, translation: [0, 0]}\n";
  EXPECT_TRUE(
      throwsNaming([&] { parse("{name: p, model: m.ply, grasps: bad.yaml}"); }, "bad.yaml: grasps[0].translation"));
  std::ofstream(pathOf("typo.yaml")) << "grasp:\n  - {name: a}\n";
  EXPECT_TRUE(throwsNaming([&] { parse("{name: p, model: m.ply, grasps: typo.yaml}"); }, "grasp"));
}

TEST_F(RecipeGrasps, ARecipeWithoutGraspsGetsThemGeneratedFromItsModel) {
  io::writeMesh(pathOf("part.ply"), simulation::makePart("l_bracket").mesh);
  writeGraspsFile(pathOf("taught.yaml"), someGrasps());
  const CellConfig config =
      parse("{name: generated, model: part.ply}, {name: taught, model: part.ply, grasps: taught.yaml}");
  EXPECT_TRUE(config.recipes[0].grasps.empty());
  const auto setup = prepareCell(config);
  const std::vector<picking::Grasp>& generated = setup->recipes[0].picking.grasps;
  ASSERT_FALSE(generated.empty());
  for (const picking::Grasp& grasp : generated) {
    EXPECT_NE(grasp.name.find("suction"), std::string::npos) << grasp.name;  // the default gripper
    EXPECT_GT(grasp.quality, 0.0);
  }
  // Grasps given take precedence: nothing is generated for them.
  ASSERT_EQ(setup->recipes[1].picking.grasps.size(), 2u);
  EXPECT_EQ(setup->recipes[1].picking.grasps[0].name, someGrasps()[0].name);
}

// A recipe that gives no symmetry gets the one its model's mesh shows; one that gives it keeps it.
TEST_F(RecipeGrasps, ARecipeWithoutASymmetryTakesTheOneItsMeshShows) {
  io::writeMesh(pathOf("magnet.ply"), simulation::makePart("ring_magnet").mesh);
  io::writeMesh(pathOf("gear.ply"), simulation::makePart("gear").mesh);
  const CellConfig config = parse(
      "{name: magnet, model: magnet.ply}, {name: gear, model: gear.ply}, "
      "{name: told, model: gear.ply, symmetry: {order: 2, axis: [1, 0, 0]}}");
  EXPECT_FALSE(config.recipes[0].symmetry.has_value());
  const auto setup = prepareCell(config);
  const picking::PartSymmetry& magnet = setup->recipes[0].picking.symmetry;
  ASSERT_TRUE(magnet.continuous_axis.has_value());
  EXPECT_GT(std::abs(magnet.continuous_axis->z()), 0.999);
  EXPECT_EQ(magnet.discrete.size(), 2u);                               // and flipped over
  EXPECT_EQ(setup->recipes[1].picking.symmetry.discrete.size(), 24u);  // 12 turns, each flipped
  EXPECT_FALSE(setup->recipes[1].picking.symmetry.continuous_axis.has_value());
  EXPECT_EQ(setup->recipes[2].picking.symmetry.discrete.size(), 2u);  // as told
}

TEST_F(RecipeGrasps, AGripperThatFitsNowhereStopsTheCellNamingTheRecipe) {
  io::writeMesh(pathOf("magnet.ply"), simulation::makePart("ring_magnet").mesh);  // 13 mm wide: no 16 mm cup seals
  const CellConfig config = parse("{name: magnet, model: magnet.ply}", "picking: {gripper: {cup_diameter: 0.016}}\n");
  EXPECT_TRUE(throwsNaming([&] { prepareCell(config); }, "recipe magnet"));
}

}  // namespace
}  // namespace binpick::cell
