#include <ctime>
#include <filesystem>
#include <fstream>
#include <utility>

#include "binpick/cell/artefact_store.hpp"
#include "binpick/core/component_logger.hpp"
#include "binpick/core/error.hpp"
#include "binpick/io/geometry_io.hpp"
#include "binpick/io/image_file.hpp"
#include "cycle_names.hpp"
#include "cycle_rotation.hpp"

namespace binpick::cell {

namespace fs = std::filesystem;
using namespace artefacts_detail;

namespace {

[[noreturn]] void fail(const fs::path& path, const std::string& what) {
  throw core::Error(path.string() + ": " + what);
}

void createStoreDirectory(const fs::path& directory) {
  std::error_code error;
  fs::create_directories(directory, error);
  if (error) fail(directory, "cannot create the artefact directory: " + error.message());
  if (!fs::is_directory(directory, error)) fail(directory, "the artefact directory is not a directory");
}

void removeInterruptedSaves(const fs::path& directory) {
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(directory, error)) {
    if (!isPartialCycleName(entry.path().filename().string())) continue;
    std::error_code remove_error;
    fs::remove_all(entry.path(), remove_error);
    if (remove_error) fail(entry.path(), "cannot remove an interrupted save: " + remove_error.message());
    core::componentLogger("artefacts")->info("removed an interrupted save: {}", entry.path().string());
  }
  if (error) fail(directory, "cannot list the artefact directory: " + error.message());
}

// A name neither saved nor being saved: cycle numbers repeat after a restart, seconds too.
fs::path freshCyclePath(const fs::path& directory, uint64_t cycle) {
  const auto now = std::chrono::system_clock::now();
  for (uint32_t suffix = 0;; ++suffix) {
    const std::string name = cycleDirectoryName(cycle, now, suffix);
    std::error_code ignored;
    if (!fs::exists(directory / name, ignored) && !fs::exists(directory / (kPartialPrefix + name), ignored)) {
      return directory / name;
    }
  }
}

void writeText(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (!out) fail(path, "cannot write the file");
}

// "20261201T161500Z" (UTC), as cycle directory names have it.
std::chrono::system_clock::time_point timeOfName(const std::string& timestamp) {
  std::tm utc{};
  if (!strptime(timestamp.c_str(), "%Y%m%dT%H%M%SZ", &utc)) return {};
  return std::chrono::system_clock::from_time_t(timegm(&utc));
}

// Writes the cycle's items into `directory`, which must not exist yet.
void writeCycle(const fs::path& directory, const CycleArtefacts& cycle, const ArtefactParams& params) {
  std::error_code error;
  if (!fs::create_directory(directory, error))
    fail(directory, "cannot create: " + (error ? error.message() : "it exists"));
  // Empty items are skipped, not refused: a cycle that reconstructed nothing is worth keeping.
  if (params.capture && cycle.capture && !cycle.capture->images.empty())
    io::writeCapture((directory / "capture").string(), *cycle.capture, params.threads);
  if (params.cloud && cycle.cloud && !cycle.cloud->empty())
    io::writePointCloud((directory / "cloud.ply").string(), *cycle.cloud, io::Encoding::Binary);
  if (params.detections && !cycle.detections_json.empty())
    writeText(directory / "detections.json", cycle.detections_json);
  if (params.overlay && cycle.overlay && !cycle.overlay->empty())
    io::writeImageFile((directory / "overlay.png").string(), *cycle.overlay);
}

// Called inside a catch block: the same failure, as a core::Error naming the cycle directory.
[[noreturn]] void rethrowNaming(const fs::path& cycle_directory, uint64_t cycle) {
  const std::string prefix = "cannot save cycle " + std::to_string(cycle) + " to " + cycle_directory.string() + ": ";
  try {
    throw;
  } catch (const core::Error& error) {
    throw core::Error(prefix + error.what());
  } catch (const fs::filesystem_error& error) {
    throw core::Error(prefix + error.what());
  } catch (const cv::Exception& error) {
    throw core::Error(prefix + error.what());
  }
}

}  // namespace

ArtefactStore::ArtefactStore(ArtefactParams params) : params_(std::move(params)) {
  params_.validate();
  createStoreDirectory(params_.directory);
  removeInterruptedSaves(params_.directory);
}

std::string ArtefactStore::save(const CycleArtefacts& cycle) {
  const fs::path cycle_directory = freshCyclePath(params_.directory, cycle.cycle);
  const fs::path partial = cycle_directory.parent_path() / (kPartialPrefix + cycle_directory.filename().string());
  try {
    writeCycle(partial, cycle, params_);
    // Only complete cycles carry a cycle name: a crash leaves a partial directory, removed on
    // the next start, never a cycle directory missing half its files.
    fs::rename(partial, cycle_directory);
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(partial, ignored);
    rethrowNaming(cycle_directory, cycle.cycle);
  }
  core::componentLogger("artefacts")->debug("saved cycle {} to {}", cycle.cycle, cycle_directory.string());
  applyBounds(params_.directory, cycle_directory.filename().string(), params_.max_cycles, params_.max_bytes);
  return cycle_directory.string();
}

std::vector<std::string> ArtefactStore::cycles() const {
  std::vector<std::string> paths;
  for (const KeptCycle& cycle : listCycles(params_.directory)) paths.push_back(cycle.path.string());
  return paths;
}

std::vector<SavedCycleDirectory> savedCycleDirectories(const std::string& directory) {
  std::vector<SavedCycleDirectory> saved;
  try {
    for (const KeptCycle& cycle : listCycles(directory)) {
      // Numbers beyond 19 digits do not fit; no cell counts that far.
      if (cycle.name.number.size() > 19) continue;
      saved.push_back({std::stoull(cycle.name.number), cycle.path.string(), timeOfName(cycle.name.timestamp)});
    }
  } catch (const std::exception&) {  // the directory changed under the listing: none this time
    return {};
  }
  return saved;
}

void ArtefactParams::validate() const {
  const std::string owner = "artefacts";
  core::requireField(!directory.empty(), owner, "directory", "a directory path", "\"\"");
  core::requireField(max_cycles >= 1, owner, "max_cycles", ">= 1", max_cycles);
  core::requireField(max_bytes >= 1, owner, "max_bytes", ">= 1", max_bytes);
  core::requireField(threads >= 0, owner, "threads", ">= 0 (0: all cores)", threads);
}

}  // namespace binpick::cell
