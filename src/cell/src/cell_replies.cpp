#include "cell_replies.hpp"

#include <algorithm>
#include <utility>
#include <vector>

namespace binpick::cell {
namespace {

using robot::Command;
using robot::Reply;
using robot::Status;

Reply make(Command command, Status status, std::vector<int32_t> integers = {}) {
  Reply reply;
  reply.command = command;
  reply.status = status;
  reply.integers = std::move(integers);
  return reply;
}

}  // namespace

int32_t clampToInt32(uint64_t value) { return static_cast<int32_t>(std::min<uint64_t>(value, INT32_MAX)); }

Reply pingReply() { return make(Command::Ping, Status::Ok); }

Reply statusReply(int32_t state, int32_t model, uint64_t cycles_done) {
  return make(Command::Status, Status::Ok, {state, model, clampToInt32(cycles_done)});
}

Reply triggerReply(Status status, uint64_t cycle) { return make(Command::Trigger, status, {clampToInt32(cycle)}); }

Reply nextPickReply(const picking::Pick& pick, std::size_t remaining) {
  Reply reply = make(Command::NextPick, Status::Ok, {clampToInt32(remaining), pick.object, pick.grasp});
  reply.T_base_tool = pick.T_base_grasp;
  return reply;
}

Reply nextReply(Status status) { return make(Command::NextPick, status, {0, kNoId, kNoId}); }

Reply failedReply(Status status, int32_t object) { return make(Command::PickFailed, status, {object}); }

Reply modelReply(Status status, int32_t model) { return make(Command::SelectModel, status, {model}); }

Reply refusedReply(Command command, Status status) { return make(command, status); }

}  // namespace binpick::cell
