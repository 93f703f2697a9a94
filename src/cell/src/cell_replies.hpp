#pragma once
// The service's replies, one builder per command. Each command's reply carries the same integers
// whatever its status (docs/robot-protocol.md, "Reply shapes"), so that a robot program reads a
// fixed number of fields: counts are 0 and ids -1 when there is nothing to tell. The exception is
// unknown_command and bad_message: they answer a request that was not understood as written, and
// carry no integers, like the server's own answers to malformed requests.
#include <cstdint>
#include <optional>

#include "binpick/picking/picking.hpp"
#include "binpick/robot/protocol.hpp"

namespace binpick::cell {

constexpr int32_t kNoId = -1;  // an object, grasp or model id that is not there

// Counters on the wire are int32.
int32_t clampToInt32(uint64_t value);

robot::Reply pingReply();
// state (CellState), selected model index, cycles done.
robot::Reply statusReply(int32_t state, int32_t model, uint64_t cycles_done);
// The cycle this TRIGGER started; 0 when it started none (busy, unknown_model, ...).
robot::Reply triggerReply(robot::Status status, uint64_t cycle);
// ok: picks remaining after this one, object id, grasp id and the pose. Otherwise 0, -1, -1.
robot::Reply nextPickReply(const picking::Pick& pick, std::size_t remaining);
robot::Reply nextReply(robot::Status status);
// The object the request named (its argument, else the last pick's object; -1: none).
robot::Reply failedReply(robot::Status status, int32_t object);
// The model index selected after the request (unknown_model: the one still selected).
robot::Reply modelReply(robot::Status status, int32_t model);
// unknown_command or bad_message for `command`: no integers.
robot::Reply refusedReply(robot::Command command, robot::Status status);

}  // namespace binpick::cell
