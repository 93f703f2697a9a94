#pragma once
// A capture as the decoder reads it, whatever rig took it. Real projectors show their own
// sequences: OpenCV's GrayCodePattern puts white and black last, phase-shift rigs often show no
// white and black, some Gray-code rigs no inverses, and many code blocks of projector pixels
// (PatternSetSpec::code_step). The decoder reads one layout: binpick's own order, in codes. This
// puts the images in that order and makes up the patterns a rig did not show:
//   white and black: the brighter and darker of the coarsest column bit and its inverse (one of
//     the two lights every pixel the projector reaches), else the phase images' mean plus and
//     minus their amplitude;
//   a Gray bit's inverse: white + black - the bit (its threshold is then the mid-level of white
//     and black, the usual choice of rigs without inverses; with made-up white and black, the
//     phase images' mean).
// Internal to the decoder. Stateless: thread-safe.
#include <string>
#include <vector>

#include "binpick/io/capture.hpp"

namespace binpick::reconstruction::detail {

struct CompleteCapture {
  io::Capture capture;               // binpick's order, in codes (pattern_set.code_step 1)
  int code_step = 1;                 // projector pixels per code of the original capture
  std::vector<std::string> made_up;  // the patterns the capture lacked, in the order above
};

// Throws core::Error naming the first problem: a pattern name no pattern has or the set does not
// code (an axis it has not, a bit beyond its Gray code, a phase step beyond its steps), a pattern
// listed twice, a Gray bit or phase step missing, white without black, nothing to make white and
// black from, or images that do not match the list (count, size, type).
CompleteCapture completeCapture(const io::Capture& capture);

// The decoded coordinate of a code in projector pixels: the centre of its block of code_step
// pixels (pixel centres at integers).
inline float projectorPixelOfCode(float code, int code_step) {
  return code * static_cast<float>(code_step) + 0.5f * static_cast<float>(code_step - 1);
}

}  // namespace binpick::reconstruction::detail
