#include "binpick/cell/cell_setup.hpp"

#include "binpick/acquisition/aravis_camera.hpp"
#include "binpick/core/component_logger.hpp"
#include "binpick/core/stopwatch.hpp"
#include "binpick/estimation/config.hpp"
#include "binpick/estimation/model_cache.hpp"
#include "binpick/io/geometry_io.hpp"
#include "binpick/io/rig_calibration.hpp"
#include "binpick/picking/grasp_generation.hpp"

namespace binpick::cell {
namespace {

// The recipe's symmetry, or the one its model's mesh shows (logged: a part taken for revolved, or
// not, changes every grasp the planner tries).
picking::PartSymmetry recipeSymmetry(const RecipeConfig& config, const io::ModelGeometry& geometry) {
  if (config.symmetry) return *config.symmetry;
  if (!geometry.hasMesh()) return {};
  const core::Stopwatch stopwatch;
  const io::FoundSymmetry found = io::findSymmetry(geometry.mesh);
  core::componentLogger("cell")->info("recipe {}: symmetry from the model's mesh: {} ({:.0f} ms)", config.name,
                                      found.description, stopwatch.elapsedMs());
  return found.symmetry;
}

// A recipe without grasps: generated from its model (mesh or cloud with normals) for the cell's
// gripper, one per symmetry class.
std::vector<picking::Grasp> generatedGrasps(const RecipeConfig& config, const io::ModelGeometry& geometry,
                                            const picking::PartSymmetry& symmetry,
                                            const picking::PickParams& cell_picking) {
  const core::Stopwatch stopwatch;
  const picking::GraspGenerationParams params;
  std::vector<picking::Grasp> grasps;
  try {
    grasps = geometry.hasMesh() ? picking::generateGrasps(geometry.mesh, cell_picking.gripper, symmetry, params)
                                : picking::generateGrasps(geometry.cloud, cell_picking.gripper, symmetry, params);
  } catch (const core::Error& e) {
    throw core::Error(config.model_file + ": recipe " + config.name + ": cannot generate grasps: " + e.what());
  }
  if (grasps.empty()) {
    throw core::Error(config.model_file + ": recipe " + config.name + ": the " +
                      picking::gripperTypeName(cell_picking.gripper.type) +
                      " gripper fits nowhere on the model; write the recipe's grasps by hand");
  }
  const double ms = stopwatch.elapsedMs();
  core::componentLogger("cell")->info(
      "recipe {}: {} {} grasps generated from the model in {:.0f} ms (best: {}, quality {:.2f})", config.name,
      grasps.size(), picking::gripperTypeName(cell_picking.gripper.type), ms, grasps.front().name,
      grasps.front().quality);
  return grasps;
}

// The cache only makes restarts fast: one that cannot be written (a read-only or missing
// directory) costs the next start the preparation again, never the start itself.
estimation::PreparedModel preparedModel(const RecipeConfig& config, const estimation::ModelParams& params,
                                        bool& from_cache) {
  if (config.model_cache.empty()) return estimation::prepareModel(io::readModelGeometry(config.model_file), params);
  std::string write_problem;
  estimation::PreparedModel model =
      estimation::loadOrPrepareModel(config.model_file, params, config.model_cache, &from_cache, &write_problem);
  if (!write_problem.empty()) {
    core::componentLogger("cell")->warn(
        "recipe {}: the model was prepared in memory, but its cache cannot be written ({}); the next "
        "start prepares it again",
        config.name, write_problem);
  }
  return model;
}

Recipe prepareRecipe(const RecipeConfig& config, const picking::PickParams& cell_picking) {
  estimation::EstimationConfig settings;
  if (!config.settings_file.empty()) settings = estimation::loadEstimationConfig(config.settings_file);
  for (const std::string& warning : settings.warnings) core::componentLogger("cell")->warn("{}", warning);
  Recipe recipe;
  recipe.name = config.name;
  estimation::PreparedModel model = preparedModel(config, settings.model, recipe.model_from_cache);
  recipe.detector = std::make_shared<const estimation::Detector>(std::move(model), settings.detector);
  recipe.picking = cell_picking;
  const bool needs_geometry = !config.symmetry || config.grasps.empty();
  const io::ModelGeometry geometry = needs_geometry ? io::readModelGeometry(config.model_file) : io::ModelGeometry{};
  recipe.picking.symmetry = recipeSymmetry(config, geometry);
  // Hand-written (or file) grasps take precedence over generated ones.
  recipe.picking.grasps =
      config.grasps.empty() ? generatedGrasps(config, geometry, recipe.picking.symmetry, cell_picking) : config.grasps;
  return recipe;
}

void prepareReconstructor(CellSetup& setup) {
  if (setup.config.calibration.empty()) {
    setup.calibration_problem = "no calibration file is configured";
    return;
  }
  try {
    const io::RigCalibration rig = io::readRigCalibration(setup.config.calibration);
    setup.reconstructor = std::make_shared<const reconstruction::Reconstructor>(rig, setup.config.reconstruction);
  } catch (const core::Error& e) {
    setup.calibration_problem = e.what();
  }
}

}  // namespace

int CellSetup::recipeIndex(const std::string& name_or_index) const {
  for (std::size_t i = 0; i < recipes.size(); ++i) {
    if (recipes[i].name == name_or_index || std::to_string(i) == name_or_index) return static_cast<int>(i);
  }
  return -1;
}

std::shared_ptr<const CellSetup> prepareCell(CellConfig config) {
  const core::Stopwatch stopwatch;
  auto setup = std::make_shared<CellSetup>();
  setup->config = std::move(config);
  for (const RecipeConfig& recipe : setup->config.recipes) {
    setup->recipes.push_back(prepareRecipe(recipe, setup->config.picking));
  }
  prepareReconstructor(*setup);
  setup->prepare_ms = stopwatch.elapsedMs();
  return setup;
}

std::string calibrationLoss(const CellSetup& running, const CellSetup& next) {
  if (running.reconstructor && !next.reconstructor) {
    return "the cell would lose its rig calibration (" + next.calibration_problem + ")";
  }
  if (running.config.T_base_camera && !next.config.T_base_camera) {
    return "the cell would lose its hand-eye calibration (hand_eye.T_base_camera is not set)";
  }
  return "";
}

std::unique_ptr<acquisition::CaptureSource> makeCaptureSource(const SourceConfig& source) {
  if (source.mode == SourceConfig::Mode::Replay) return acquisition::makeReplaySource(source.replay);
  const LiveSourceConfig& live = source.live;
  auto projector =
      live.trigger == "gpio" ? acquisition::makeGpioTrigger(live.gpio) : acquisition::makeFreeRunningProjector();
  return acquisition::makeLiveSource(acquisition::makeAravisCamera(live.camera), std::move(projector), live.live);
}

}  // namespace binpick::cell
