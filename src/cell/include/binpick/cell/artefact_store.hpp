#pragma once
// Saved cycle artefacts: for each pick cycle worth keeping, a directory holding what the cell saw
// and decided, so that a bad pick can be understood afterwards. Layout of one cycle directory:
//   DIR/cycle-<cycle, 6+ digits>-<UTC, 20261201T161500Z>[-<n>]/
//     capture/         the pattern images (a capture directory, docs/capture-format.md)
//     cloud.ply        the reconstructed cloud (binary PLY)
//     detections.json  the caller's text
//     overlay.png      the camera image with the detections drawn in (overlay.hpp)
// The optional "-<n>" keeps names unique when a cycle number repeats within one second (after a
// restart). A cycle is written into "DIR/.partial-<name>" and renamed when complete: a cycle
// directory is always whole. The store bounds DIR by count and by size, deleting the oldest cycle
// directories; it only ever deletes directories named like its own, so DIR may hold other files.
//
// Not thread-safe: one thread at a time, and one store per directory (the constructor deletes
// the partial directories of an interrupted save, which would be another store's saves in
// progress).
#include <chrono>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "binpick/io/capture.hpp"
#include "binpick/io/point_cloud.hpp"

namespace binpick::cell {

struct ArtefactParams {
  std::string directory;  // where cycle directories go (created if missing)
  int max_cycles = 50;    // newest kept (>= 1); older cycle directories deleted
  // Also bounded in size: bytes of the files of all cycle directories (>= 1). The oldest go first;
  // the newest is always kept, even when it alone is larger.
  uint64_t max_bytes = 2ull << 30;
  // What is saved, when the cycle provides it.
  bool capture = true, cloud = true, detections = true, overlay = true;
  // Threads encoding the capture's PNG images (0: all cores). One by default, so that saving
  // does not compete with the next pick cycle for the cores.
  int threads = 1;
  void validate() const;  // throws core::Error naming the field
};

// One cycle's artefacts; null and empty items (no images, no points, no text) are not saved,
// so that a cycle that found nothing still leaves what it did have. The pointees must outlive
// save().
struct CycleArtefacts {
  uint64_t cycle = 0;
  const io::Capture* capture = nullptr;   // capture/
  const io::PointCloud* cloud = nullptr;  // cloud.ply
  std::string detections_json;            // detections.json, written as given
  const cv::Mat* overlay = nullptr;       // overlay.png (8- or 16-bit; 1, 3 or 4 channels)
};

class ArtefactStore {
 public:
  // Validates `params`, creates the directory and removes leftovers of an interrupted save.
  // Throws core::Error naming the directory when it cannot be created or is not a directory.
  explicit ArtefactStore(ArtefactParams params);

  // Writes the cycle's directory, then deletes the oldest cycle directories beyond the bounds
  // (a directory that cannot be deleted is logged and skipped). Returns the new cycle directory.
  // On failure throws core::Error naming the cycle directory and what went wrong, leaving no
  // partial directory behind; the bounds are not applied then.
  std::string save(const CycleArtefacts& cycle);

  // The kept cycle directories (full paths), oldest first.
  std::vector<std::string> cycles() const;

  const ArtefactParams& params() const { return params_; }

 private:
  ArtefactParams params_;
};

// A kept cycle directory, as readers of the artefacts (the web view) find it.
struct SavedCycleDirectory {
  uint64_t cycle = 0;
  std::string path;
  std::chrono::system_clock::time_point saved_at;  // from its name: when its saving began (1 s steps)
};

// The cycle directories in `directory` (real directories, not symlinks), oldest first; cycle
// numbers repeat after a restart, so a number may appear more than once. Read-only: safe on any
// thread beside the store saving into it (a directory it deletes meanwhile is missing from the
// list, or gone when opened). Empty when `directory` cannot be read.
std::vector<SavedCycleDirectory> savedCycleDirectories(const std::string& directory);

}  // namespace binpick::cell
