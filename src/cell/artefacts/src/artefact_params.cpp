#include "binpick/cell/artefact_store.hpp"
#include "binpick/io/error.hpp"

namespace binpick::cell {

void ArtefactParams::validate() const {
  const std::string owner = "artefacts";
  requireField(!directory.empty(), owner, "directory", "a directory path", "\"\"");
  requireField(max_cycles >= 1, owner, "max_cycles", ">= 1", max_cycles);
  requireField(max_bytes >= 1, owner, "max_bytes", ">= 1", max_bytes);
  requireField(threads >= 0, owner, "threads", ">= 0 (0: all cores)", threads);
}

}  // namespace binpick::cell
