#pragma once
// What a rig projects, image by image: binpick's own sequence or another rig's (a projector's
// sequence is often fixed in its flash), named by a preset or described in a YAML file that a
// user writes (docs/real-rigs.md):
//
//   projector: {width: 1920, height: 1080}
//   code_step: 2                  # projector pixels per code (default 1)
//   gray_unit: 16                 # projector pixels per Gray-code word (default code_step);
//                                 # a complementary Gray code: half the phase period
//   phase: {steps: 4, period: 32} # only with phase images; the period in projector pixels
//                                 # (direction: -1 and offset_deg: D for another rig's steps)
//   images:                       # in capture order
//     - gray: columns             # every Gray bit of the columns:
//       inverses: after_each      #   after_each (default) | after_all | none
//       order: msb_first          #   msb_first (default) | lsb_first
//     - gray: rows
//     - phase: columns            # phase_col_0 .. phase_col_{steps-1}
//     - white                     # one pattern by name: white, black, gray_row_03_inv, ...
//     - black
//
// The names are the capture format's (docs/capture-format.md); the decoder takes them in any
// order, with or without white and black and inverses (capture_completion). Thread-safe.
#include <string>
#include <vector>

#include "binpick/io/capture.hpp"

namespace binpick::reconstruction {

struct RigSequence {
  io::PatternSetSpec spec;            // projector size, code step, coded axes, phase
  std::vector<std::string> patterns;  // one name per image, in capture order
};

// "binpick": binpick's own (white, black, per axis its Gray pairs then phase steps; from `spec`).
// "opencv-graycode": OpenCV's structured_light::GrayCodePattern: the column Gray bits, most
// significant first, each followed by its inverse, the same for rows, then white and black.
// `spec` gives the projector size and code step (and for binpick the axes and phase).
// Throws core::Error listing the presets for another name.
RigSequence presetSequence(const std::string& name, const io::PatternSetSpec& spec);
const std::vector<std::string>& sequencePresetNames();

// Throws core::Error "PATH: ..." naming the entry and what is wrong with it.
RigSequence readRigSequence(const std::string& path);
RigSequence parseRigSequence(const std::string& yaml_text, const std::string& origin);

}  // namespace binpick::reconstruction
