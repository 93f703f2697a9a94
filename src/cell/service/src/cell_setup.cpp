#include "binpick/cell/cell_setup.hpp"

#include <chrono>

#include "binpick/acquisition/aravis_camera.hpp"
#include "binpick/estimation/config.hpp"
#include "binpick/estimation/model_cache.hpp"
#include "binpick/io/rig_calibration.hpp"

namespace binpick::cell {
namespace {

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
  recipe.picking.grasps = config.grasps;
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
