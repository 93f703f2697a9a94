#pragma once
// One view of a camera + projector calibration: a capture of the board under the full pattern set
// (column and row codes), turned into the board's corners in the camera image (detectBoard on the
// white image) and in the projector image (findProjectorCorners on the decoded capture).
// A board that is not found is not an error here: the view says why, and the calibration
// reports it by name and goes on without it. Stateless functions: thread-safe.
#include <string>

#include "binpick/calibration/board_detection.hpp"
#include "binpick/calibration/board_layout.hpp"
#include "binpick/calibration/projector_corners.hpp"
#include "binpick/io/capture.hpp"
#include "binpick/reconstruction/decoder.hpp"

namespace binpick::calibration {

struct RigViewParams {
  BoardDetectionParams detection;
  reconstruction::DecodeParams decode;
  ProjectorCornerParams projector;
  void validate() const;  // throws core::Error naming the member and field
};

struct RigViewTimings {  // milliseconds
  double decode = 0.0;
  double detect = 0.0;
  double projector_corners = 0.0;
};

struct RigView {
  std::string name;  // the capture directory (or another label), used in every message
  int camera_width = 0, camera_height = 0;
  int projector_width = 0, projector_height = 0;  // the capture's pattern set
  BoardDetection board;                           // the corners in the camera image; board.problem if not found
  ProjectorCorners projector;                     // those of them the projector's pixels were found for
  RigViewTimings timings;
};

// Throws core::Error "NAME: ..." when the capture cannot serve a calibration: no column or
// row codes, no white image, or images the decoder refuses (decoder.hpp).
RigView measureRigView(const io::Capture& capture, const std::string& name, const BoardLayout& layout,
                       const RigViewParams& params = {});
// readCapture(directory) then measureRigView, named by the directory. Throws core::Error
// naming the directory on an unreadable or incomplete capture too.
RigView readRigView(const std::string& directory, const BoardLayout& layout, const RigViewParams& params = {});

}  // namespace binpick::calibration
