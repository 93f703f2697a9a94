#pragma once
// Saves a cycle's artefacts (capture, cloud, detections JSON, overlay PNG) on its own thread, so
// that writing ~50 images never delays the robot. One save runs at a time and one more may wait;
// a cycle arriving while both places are taken is not saved (logged).
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "binpick/cell/artefact_store.hpp"
#include "binpick/cell/cell_setup.hpp"
#include "binpick/cell/pick_cycle.hpp"

namespace binpick::cell {

struct SavedCycle {
  uint64_t number = 0;
  std::shared_ptr<const CellSetup> setup;
  int recipe = 0;
  io::Capture capture;
  CycleOutcome outcome;
};

class ArtefactSaver {
 public:
  explicit ArtefactSaver(const ArtefactParams& params);
  ~ArtefactSaver();  // finishes the running and the waiting save
  void offer(SavedCycle cycle);

 private:
  void run();
  ArtefactStore store_;
  std::mutex mutex_;
  std::condition_variable wakeup_;
  std::optional<SavedCycle> waiting_;
  bool stopping_ = false;
  std::thread thread_;
};

// The detections and picks of a cycle as JSON text (detections.json).
std::string cycleJson(const SavedCycle& cycle);
// The white image with the detections and picks drawn on it.
cv::Mat cycleOverlay(const SavedCycle& cycle);

}  // namespace binpick::cell
