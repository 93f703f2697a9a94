#include "binpick/cell/cell_setup.hpp"

#include <chrono>

#include "binpick/acquisition/aravis_camera.hpp"
#include "binpick/cell/grasp_generation.hpp"
#include "binpick/estimation/config.hpp"
#include "binpick/estimation/model_cache.hpp"
#include "binpick/io/geometry_io.hpp"
#include "binpick/io/rig_calibration.hpp"
#include "service_logger.hpp"

namespace binpick::cell {
namespace {

// A recipe without grasps: generated from its model (mesh or cloud with normals) for the cell's
// gripper, one per symmetry class.
std::vector<Grasp> generatedGrasps(const RecipeConfig& config, const PickParams& cell_picking) {
  const auto start = std::chrono::steady_clock::now();
  const ModelGeometry geometry = readModelGeometry(config.model_file);
  const GraspGenerationParams params;
  std::vector<Grasp> grasps;
  try {
    grasps = geometry.hasMesh() ? generateGrasps(geometry.mesh, cell_picking.gripper, config.symmetry, params)
                                : generateGrasps(geometry.cloud, cell_picking.gripper, config.symmetry, params);
  } catch (const Error& e) {
    throw Error(config.model_file + ": recipe " + config.name + ": cannot generate grasps: " + e.what());
  }
  if (grasps.empty()) {
    throw Error(config.model_file + ": recipe " + config.name + ": the " + gripperTypeName(cell_picking.gripper.type) +
                " gripper fits nowhere on the model; write the recipe's grasps by hand");
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  logger()->info("recipe {}: {} {} grasps generated from the model in {:.0f} ms (best: {}, quality {:.2f})",
                 config.name, grasps.size(), gripperTypeName(cell_picking.gripper.type), ms, grasps.front().name,
                 grasps.front().quality);
  return grasps;
}

Recipe prepareRecipe(const RecipeConfig& config, const PickParams& cell_picking) {
  estimation::EstimationConfig settings;
  if (!config.settings_file.empty()) settings = estimation::loadEstimationConfig(config.settings_file);
  Recipe recipe;
  recipe.name = config.name;
  estimation::PreparedModel model =
      config.model_cache.empty()
          ? estimation::prepareModel(readModelGeometry(config.model_file), settings.model)
          : estimation::loadOrPrepareModel(config.model_file, settings.model, config.model_cache,
                                           &recipe.model_from_cache);
  recipe.detector = std::make_shared<const estimation::Detector>(std::move(model), settings.detector);
  recipe.picking = cell_picking;
  // Hand-written (or file) grasps take precedence over generated ones.
  recipe.picking.grasps = config.grasps.empty() ? generatedGrasps(config, cell_picking) : config.grasps;
  recipe.picking.symmetry = config.symmetry;
  return recipe;
}

void prepareReconstructor(CellSetup& setup) {
  if (setup.config.calibration.empty()) {
    setup.calibration_problem = "no calibration file is configured";
    return;
  }
  try {
    const RigCalibration rig = readRigCalibration(setup.config.calibration);
    setup.reconstructor = std::make_shared<const reconstruction::Reconstructor>(rig, setup.config.reconstruction);
  } catch (const Error& e) {
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
  const auto start = std::chrono::steady_clock::now();
  auto setup = std::make_shared<CellSetup>();
  setup->config = std::move(config);
  for (const RecipeConfig& recipe : setup->config.recipes) {
    setup->recipes.push_back(prepareRecipe(recipe, setup->config.picking));
  }
  prepareReconstructor(*setup);
  setup->prepare_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return setup;
}

std::unique_ptr<acquisition::CaptureSource> makeCaptureSource(const SourceConfig& source) {
  if (source.mode == SourceConfig::Mode::Replay) return acquisition::makeReplaySource(source.replay);
  const LiveSourceConfig& live = source.live;
  auto projector = live.trigger == "gpio" ? acquisition::makeGpioTrigger(live.gpio)
                                          : acquisition::makeFreeRunningProjector();
  return acquisition::makeLiveSource(acquisition::makeAravisCamera(live.camera), std::move(projector), live.live);
}

}  // namespace binpick::cell
