#include "artefact_saver.hpp"

#include <algorithm>

#include "binpick/core/component_logger.hpp"
#include "overlay.hpp"

namespace binpick::cell {

ArtefactSaver::ArtefactSaver(const ArtefactParams& params) : store_(params), thread_([this] { run(); }) {}

ArtefactSaver::~ArtefactSaver() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wakeup_.notify_one();
  thread_.join();
}

void ArtefactSaver::offer(SavedCycle cycle) {
  {
    std::lock_guard lock(mutex_);
    if (waiting_)
      core::componentLogger("cell")->warn("cycle {}: artefacts not saved, two saves are pending already",
                                          waiting_->number);
    waiting_ = std::move(cycle);  // the newest cycle is the one worth keeping
  }
  wakeup_.notify_one();
}

void ArtefactSaver::run() {
  for (;;) {
    std::unique_lock lock(mutex_);
    wakeup_.wait(lock, [&] { return waiting_.has_value() || stopping_; });
    if (!waiting_) return;  // stopping with nothing left to save
    SavedCycle cycle = std::move(*waiting_);
    waiting_.reset();
    lock.unlock();
    try {
      const cv::Mat overlay = cycleOverlay(cycle);
      CycleArtefacts artefacts;
      artefacts.cycle = cycle.number;
      artefacts.capture = &cycle.capture;
      artefacts.cloud = &cycle.outcome.reconstruction.cloud;
      artefacts.detections_json = cycleJson(cycle);
      artefacts.overlay = overlay.empty() ? nullptr : &overlay;
      const std::string directory = store_.save(artefacts);
      core::componentLogger("cell")->debug("cycle {}: artefacts in {}", cycle.number, directory);
    } catch (const std::exception& e) {  // a full disk must not stop the cell
      core::componentLogger("cell")->error("cycle {}: artefacts not saved: {}", cycle.number, e.what());
    }
  }
}

cv::Mat cycleOverlay(const SavedCycle& cycle) {
  const CellSetup& setup = *cycle.setup;
  const auto& patterns = cycle.capture.metadata.patterns;
  const auto white = std::find(patterns.begin(), patterns.end(), "white");
  if (white == patterns.end() || !setup.reconstructor || !setup.config.T_base_camera) return {};
  const cv::Mat& image = cycle.capture.images.at(static_cast<std::size_t>(white - patterns.begin()));
  const Eigen::Isometry3d T_camera_base = setup.config.T_base_camera->inverse();

  std::vector<OverlayPart> parts;
  for (const estimation::Detection& detection : cycle.outcome.detection.detections) {
    OverlayPart part;
    part.T_camera_model = detection.T_camera_model.cast<double>();
    parts.push_back(part);
  }
  for (std::size_t rank = 0; rank < cycle.outcome.picks.size(); ++rank) {
    const picking::Pick& pick = cycle.outcome.picks[rank];
    OverlayPart& part = parts.at(static_cast<std::size_t>(pick.object));
    part.pick_rank = static_cast<int>(rank);
    part.T_camera_grasp = T_camera_base * pick.T_base_grasp;
  }
  const auto& recipe = setup.recipes.at(static_cast<std::size_t>(cycle.recipe));
  return renderOverlay(image, setup.reconstructor->rig().camera, recipe.detector->model().points, parts);
}

}  // namespace binpick::cell
