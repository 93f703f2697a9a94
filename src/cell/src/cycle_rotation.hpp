#pragma once
// Internal: finding the cycle directories of a store and deleting the oldest beyond its bounds.
// Touches only directories named like cycle directories. Not thread-safe (one store at a time).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "cycle_names.hpp"

namespace binpick::cell::artefacts_detail {

struct KeptCycle {
  CycleName name;
  std::filesystem::path path;
};

// The cycle directories in `directory` (directories, not symlinks to them), oldest first.
std::vector<KeptCycle> listCycles(const std::filesystem::path& directory);

// Bytes of the regular files below `path`; symlinks are not followed, unreadable entries count 0.
uint64_t bytesBelow(const std::filesystem::path& path);

// Deletes the oldest cycle directories, never `keep_name`, until at most `max_cycles` remain and
// they hold at most `max_bytes` (or only `keep_name` is left). A directory that cannot be deleted
// is logged and passed over.
void applyBounds(const std::filesystem::path& directory, const std::string& keep_name, int max_cycles,
                 uint64_t max_bytes);

}  // namespace binpick::cell::artefacts_detail
