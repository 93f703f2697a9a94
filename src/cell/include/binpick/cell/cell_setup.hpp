#pragma once
// What the settings file turns into before the first cycle: the prepared models (from their
// caches when valid: a restart takes milliseconds), the reconstructor with its calibration tables,
// and the capture source. Built at start and on every reload; immutable once built, so cycles
// share it through a shared_ptr while a reload prepares the next one.
#include <memory>
#include <string>
#include <vector>

#include "binpick/acquisition/capture_source.hpp"
#include "binpick/cell/cell_config.hpp"
#include "binpick/estimation/detector.hpp"
#include "binpick/reconstruction/reconstruction.hpp"

namespace binpick::cell {

struct Recipe {
  std::string name;
  std::shared_ptr<const estimation::Detector> detector;
  picking::PickParams picking;  // the cell's picking settings with this recipe's grasps and symmetry
  bool model_from_cache = false;
};

struct CellSetup {
  CellConfig config;
  std::vector<Recipe> recipes;
  // Null when the rig calibration is missing or unreadable (`calibration_problem` says why): the
  // service then answers TRIGGER with "calibration missing" instead of refusing to start, so a
  // cell can be brought up before it is calibrated.
  std::shared_ptr<const reconstruction::Reconstructor> reconstructor;
  std::string calibration_problem;
  double prepare_ms = 0.0;

  int recipeIndex(const std::string& name_or_index) const;  // -1 when there is none such
};

// Throws core::Error naming the file when a model or its settings are unusable. A model cache
// that cannot be read is rebuilt, one that cannot be written is logged (a warning): the model is
// then prepared in memory at every start.
std::shared_ptr<const CellSetup> prepareCell(CellConfig config);

// What a cell running on `running` would lose by switching to `next`: its rig calibration (a file
// now missing or unreadable, as while a technician recalibrates) or its hand-eye T_base_camera.
// Empty when nothing is lost. CellService::reconfigure refuses such settings as a whole: the cell
// keeps picking on what it has instead of answering "calibration missing" until someone notices.
std::string calibrationLoss(const CellSetup& running, const CellSetup& next);

// The capture source the settings describe. Live sources open the camera on the first capture.
std::unique_ptr<acquisition::CaptureSource> makeCaptureSource(const SourceConfig& source);

}  // namespace binpick::cell
