#pragma once
// Where `calibrate rig` gets its views: the capture directories of a sequence, a list of them,
// or the live path, one capture per Enter, each recorded before it is used.
#include <istream>
#include <string>
#include <vector>

#include "arguments.hpp"
#include "binpick/calibration/rig_views.hpp"

namespace binpick::cli {

// The subdirectories of `directory` that hold a capture.json, sorted by name. Throws
// core::Error naming the directory when it cannot be read or holds no capture.
std::vector<std::string> sequenceCaptures(const std::string& directory);

// Each directory read and measured, with a line per view on stderr. Throws core::Error naming
// the directory of a capture that is corrupt or cannot serve a calibration (no row codes).
std::vector<calibration::RigView> readViews(const std::vector<std::string>& directories,
                                            const calibration::BoardLayout& layout,
                                            const calibration::RigViewParams& params);

// The live path (--camera, or --fake-camera serving a recorded sequence's captures in order):
// up to `count` views, each taken when a line arrives on `input` ("q" or the end of the input
// stops early), written to RECORD/view_NNN and then measured. A view that cannot be measured is
// reported by its directory and left out. Throws core::Error when RECORD already holds
// files, or on camera errors (the views recorded so far stay on disk).
std::vector<calibration::RigView> captureLiveViews(const Arguments& args, int count, const std::string& record,
                                                   const calibration::BoardLayout& layout,
                                                   const calibration::RigViewParams& params, std::istream& input);

}  // namespace binpick::cli
