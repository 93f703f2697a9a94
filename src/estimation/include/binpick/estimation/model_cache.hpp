#pragma once
// Prepared-model cache files: the sampled model, its parameters, its symmetry, its near symmetries,
// the PPF table and the outline's (boundary.hpp), so that a service starts in milliseconds instead of redoing the work
// that depends on the model alone. The table is mapped from the file and used where it lies, never read or copied.
// Versioned and checksummed; a truncated, corrupt, foreign or outdated file is rejected with core::Error, never
// trusted. Free functions without shared state: thread-safe (for different files).
#include <cstdint>
#include <string>

#include "binpick/estimation/model.hpp"

namespace binpick::estimation {

// 2: max_pairs_per_feature; 3: the fine surface; 4: mapped (8-aligned arrays, a word-wise
// checksum), the symmetry's references, the near symmetries and the outline's model side;
// 5: pair keys from the cosines of the angles (a few pairs at bin borders change key)
constexpr uint32_t kModelCacheVersion = 5;

// `source_fingerprint` identifies what the model was built from (see fingerprintFile): a cache is
// only reused for the same source and parameters.
void saveModelCache(const PreparedModel& model, uint64_t source_fingerprint, const std::string& path);

struct CachedModel {
  PreparedModel model;
  uint64_t source_fingerprint = 0;
};
CachedModel loadModelCache(const std::string& path);

// FNV-1a 64 of a file's bytes; throws core::Error when it cannot be read.
uint64_t fingerprintFile(const std::string& path);

// The cache at `cache_path` when it exists and was built from the same source with the same
// params; otherwise the model is prepared from `model_path` and the cache (re)written. `reused`
// tells which happened. A cache that cannot be written throws core::Error naming it, unless
// `write_problem` is given: then the prepared model is returned and the problem stored there
// (empty when the cache was reused or written), for callers to whom the cache is only a speed-up.
PreparedModel loadOrPrepareModel(const std::string& model_path, const ModelParams& params,
                                 const std::string& cache_path, bool* reused = nullptr,
                                 std::string* write_problem = nullptr);

}  // namespace binpick::estimation
