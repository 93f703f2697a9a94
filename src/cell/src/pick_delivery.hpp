#pragma once
// Whether a pick can reach the robot: its NEXT reply must encode with the robot codec, or the
// robot would get bad_message for a pick it never receives (an ASCII line longer than
// robot.max_line_length even at reduced precision, a binary field beyond int32). Checked twice:
// when the settings are read, for the widest reply the cell may send, so that settings that
// cannot carry a pick are refused at start; and for every pick of a cycle, so that a pick that
// still cannot be sent is left out and logged instead of being handed out as bad_message.
// Stateless functions: thread-safe.
#include <string>
#include <vector>

#include "binpick/picking/picking.hpp"
#include "binpick/robot/protocol.hpp"

namespace binpick::cell {

// The widest pick the start-up check allows for: every coordinate this far from the base.
constexpr double kWidestPickCoordinateMm = 9999.99;

// Throws core::Error naming the setting ("robot.max_line_length must be >= 64 ...", or
// robot.position_scale / robot.orientation_scale in binary framing) when a NEXT reply with up to
// `max_picks` - 1 picks remaining, object and grasp ids up to 99 and a pose with coordinates up
// to kWidestPickCoordinateMm, in any orientation, cannot be encoded with `codec`.
void checkPickRepliesFit(const robot::CodecParams& codec, int max_picks);

struct DeliverablePicks {
  std::vector<picking::Pick> picks;   // the picks whose NEXT reply encodes, in their order
  std::vector<std::string> problems;  // one line per pick left out: which, and why
};
DeliverablePicks deliverablePicks(std::vector<picking::Pick> picks, const robot::CodecParams& codec);

}  // namespace binpick::cell
