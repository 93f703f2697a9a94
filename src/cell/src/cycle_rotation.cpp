#include "cycle_rotation.hpp"

#include <algorithm>

#include "binpick/core/component_logger.hpp"

namespace binpick::cell::artefacts_detail {

namespace fs = std::filesystem;

namespace {

bool removeCycle(const KeptCycle& cycle) {
  std::error_code error;
  fs::remove_all(cycle.path, error);
  if (error) {
    core::componentLogger("artefacts")
        ->warn("cannot delete old cycle directory {}: {}", cycle.path.string(), error.message());
    return false;
  }
  core::componentLogger("artefacts")->debug("deleted old cycle directory {}", cycle.path.string());
  return true;
}

}  // namespace

std::vector<KeptCycle> listCycles(const fs::path& directory) {
  std::vector<KeptCycle> cycles;
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(directory, error)) {
    std::optional<CycleName> name = parseCycleDirectoryName(entry.path().filename().string());
    std::error_code status_error;
    // A symlink named like a cycle is not ours: deleting it would delete what it points to.
    if (!name || !fs::is_directory(entry.symlink_status(status_error))) continue;
    cycles.push_back({std::move(*name), entry.path()});
  }
  std::sort(cycles.begin(), cycles.end(),
            [](const KeptCycle& a, const KeptCycle& b) { return savedBefore(a.name, b.name); });
  return cycles;
}

uint64_t bytesBelow(const fs::path& path) {
  uint64_t bytes = 0;
  std::error_code error;
  const auto options = fs::directory_options::skip_permission_denied;
  for (fs::recursive_directory_iterator it(path, options, error), end; !error && it != end; it.increment(error)) {
    std::error_code status_error;
    if (!fs::is_regular_file(it->symlink_status(status_error))) continue;
    const uintmax_t size = it->file_size(status_error);
    if (!status_error) bytes += size;
  }
  return bytes;
}

void applyBounds(const fs::path& directory, const std::string& keep_name, int max_cycles, uint64_t max_bytes) {
  std::vector<KeptCycle> cycles = listCycles(directory);
  std::vector<uint64_t> sizes;
  uint64_t total = 0;
  for (const KeptCycle& cycle : cycles) total += sizes.emplace_back(bytesBelow(cycle.path));
  std::size_t count = cycles.size();
  for (std::size_t oldest = 0; oldest < cycles.size(); ++oldest) {
    const bool over = count > static_cast<std::size_t>(max_cycles) || total > max_bytes;
    if (!over) break;
    if (cycles[oldest].name.name == keep_name || !removeCycle(cycles[oldest])) continue;
    --count;
    total -= sizes[oldest];
  }
}

}  // namespace binpick::cell::artefacts_detail
