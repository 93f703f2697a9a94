#pragma once
// Internal: the names of cycle directories ("cycle-000042-20261201T161500Z", "-<n>" appended when
// that name is taken), of their partial versions (".partial-" + name), and their order.
// Stateless functions: thread-safe.
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

namespace binpick::cell::artefacts_detail {

inline const std::string kPartialPrefix = ".partial-";

struct CycleName {
  std::string name;       // the whole directory name
  std::string number;     // cycle number as written (6+ digits)
  std::string timestamp;  // 20261201T161500Z
  uint32_t suffix = 0;    // 0: none
};

// `suffix` 0 gives the plain name.
std::string cycleDirectoryName(uint64_t cycle, std::chrono::system_clock::time_point when, uint32_t suffix);
// The parts of a cycle directory name; nullopt for any other name.
std::optional<CycleName> parseCycleDirectoryName(const std::string& name);
// Whether `name` is ".partial-" followed by a cycle directory name.
bool isPartialCycleName(const std::string& name);
// Oldest first: by time, then cycle number, then suffix (cycle numbers restart with the daemon,
// the clock does not).
bool savedBefore(const CycleName& a, const CycleName& b);

}  // namespace binpick::cell::artefacts_detail
