// CellService: the robot's requests. Runs on the server thread: never blocks beyond the lock.
#include "binpick/cell/cell_service.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "binpick/core/component_logger.hpp"
#include "binpick/core/error.hpp"

#include "service_state.hpp"

namespace binpick::cell {
namespace {

using robot::Command;
using robot::Reply;
using robot::Status;

// FAILED's argument (the server has checked it is a non-negative int32).
std::optional<int32_t> parseObjectId(const std::string& text) {
  if (text.empty() || text.size() > 10 || text.find_first_not_of("0123456789") != std::string::npos) {
    return std::nullopt;
  }
  const long long value = std::stoll(text);
  if (value > INT32_MAX) return std::nullopt;
  return static_cast<int32_t>(value);
}

constexpr uint64_t kForgetCycles = 200;  // a failed place not failed again for this long is forgotten
constexpr int kMaxDoublings = 6;         // avoided at most 64 x limits.avoid_cycles

}  // namespace

// A part whose pick failed is avoided for limits.avoid_cycles cycles; each further failure at the
// same place (within the recipe's avoid_radius of an earlier one) doubles that, so that a part the
// robot cannot hold stops being offered instead of failing every few cycles.
// Counted from the last cycle numbered: one whose TRIGGER was accepted keeps the avoid list it had
// then, even if its thread reads the list after this failure, so the part is avoided from the
// cycle after it on, whenever the robot's FAILED arrives.
uint64_t CellService::State::avoidFailedPart(const Eigen::Vector3d& centre) {
  const uint64_t now = cycles_started;
  const double radius = setup->recipes.at(static_cast<std::size_t>(recipe)).picking.avoid_radius;
  avoid.erase(std::remove_if(avoid.begin(), avoid.end(),
                             [&](const AvoidEntry& e) { return e.until_cycle + kForgetCycles < now; }),
              avoid.end());
  auto same_place = std::find_if(avoid.begin(), avoid.end(),
                                 [&](const AvoidEntry& e) { return (e.centre - centre).norm() <= radius; });
  int failures = 1;
  if (same_place != avoid.end()) {
    failures = same_place->failures + 1;
    avoid.erase(same_place);
  }
  const uint64_t cycles = static_cast<uint64_t>(setup->config.limits.avoid_cycles)
                          << std::min(failures - 1, kMaxDoublings);
  avoid.push_back({centre, now + 1, now + cycles, failures});
  return cycles;
}

// The cycle checked its picks against the codec of the settings it ran on; a reload since may
// have changed the codec every robot now hears, so a pick is checked again as it is handed out.
robot::Reply CellService::State::nextPick() {
  if (latest->status != Status::Ok) return nextReply(latest->status);
  const robot::CodecParams& codec = setup->config.robot.codec;
  const auto sendable = [&](std::size_t i) {
    return robot::encodeReplyIfItFits(nextPickReply(latest->picks[i], latest->picks.size() - i - 1), codec);
  };
  while (latest->cursor < latest->picks.size() && !sendable(latest->cursor)) {
    core::componentLogger("cell")->error(
        "cycle {}: the pick of object {} cannot be sent with the reloaded robot codec: skipped", latest->number,
        latest->picks[latest->cursor].object);
    ++latest->cursor;
  }
  if (latest->cursor >= latest->picks.size()) return nextReply(Status::NoMorePicks);
  const picking::Pick& pick = latest->picks[latest->cursor++];
  if (!handed_out || handed_out->number != latest->number) {
    handed_out = HandedOutCycle{latest->number, latest->T_base_objects};
  }
  handed_out->last_object = pick.object;
  return nextPickReply(pick, latest->picks.size() - latest->cursor);
}

void CellService::State::publish() {
  const bool picks_left = latest && latest->status == Status::Ok && latest->cursor < latest->picks.size();
  const std::size_t waiting = picks_left ? latest->picks.size() - latest->cursor : 0;
  board.update([&](CellReport& report) {
    report.state = cell_state;
    report.recipe = currentRecipe().name;
    report.cycle = cycles_started;
    report.picks_waiting = waiting;
  });
}

void CellService::State::publishSetup(const acquisition::CaptureSource* new_source) {
  std::vector<std::string> names;
  for (const Recipe& r : setup->recipes) names.push_back(r.name);
  board.update([&](CellReport& report) {
    report.recipes = names;
    report.orientation = setup->config.robot.codec.orientation;
    report.capture.mode = setup->config.source.mode == SourceConfig::Mode::Replay ? "replay" : "live";
    if (new_source) report.capture.source = new_source->description();
    report.capture.calibration_problem = setup->reconstructor ? "" : setup->calibration_problem;
    report.capture.hand_eye = setup->config.T_base_camera.has_value();
  });
  publish();
}

void CellService::State::answerWaiters(Outbox& outbox) {
  for (const robot::ClientId client : next_waiters) outbox.add(client, nextPick());
  next_waiters.clear();
}

CellService::CellService(std::shared_ptr<const CellSetup> setup, std::unique_ptr<acquisition::CaptureSource> source,
                         ReplySink sink)
    : state_(std::make_unique<State>()) {
  state_->sink = std::move(sink);
  state_->setup = std::move(setup);
  state_->source = std::move(source);
  state_->last.recipe = state_->currentRecipe().name;
  if (state_->setup->config.artefacts)
    state_->saver = std::make_unique<ArtefactSaver>(*state_->setup->config.artefacts);
  const std::optional<ArtefactParams>& artefacts = state_->setup->config.artefacts;
  state_->board.update([&](CellReport& report) {
    report.started = std::chrono::system_clock::now();
    if (artefacts) report.artefact_directory = artefacts->directory;
  });
  state_->publishSetup(state_->source.get());
  state_->cycle_thread = std::thread([this] { runCycles(); });
  state_->deadline_thread = std::thread([this] { runDeadlines(); });
}

CellService::~CellService() { stop(); }

void CellService::handle(robot::ClientId client, const robot::Request& request) {
  Outbox outbox;
  {
    std::lock_guard lock(state_->mutex);
    if (std::optional<robot::Reply> reply = state_->answer(client, request)) outbox.add(client, std::move(*reply));
    state_->publish();
  }
  outbox.send(state_->sink);
}

std::optional<robot::Reply> CellService::State::answer(robot::ClientId client, const robot::Request& request) {
  const std::string argument = request.argument.value_or("");
  switch (request.command) {
    case Command::Ping: return pingReply();
    case Command::Status: return statusReply(static_cast<int32_t>(cell_state), recipe, last.cycles_done);
    case Command::SelectModel: {
      const int index = setup->recipeIndex(argument);
      if (index >= 0) recipe = index;
      return modelReply(index >= 0 ? Status::Ok : Status::UnknownModel, recipe);
    }
    case Command::Trigger: return trigger(client, request);
    case Command::NextPick:
      if (latest) return nextPick();
      if (cell_state == CellState::Idle) return nextReply(Status::NoCycle);
      next_waiters.push_back(client);
      return std::nullopt;
    case Command::PickFailed: return pickFailed(request);
    case Command::Pose:
      // Hand-eye views are recorded by the calibration tool; a robot sending them here is
      // talking to the wrong program, and the log says which one it wants.
      core::componentLogger("cell")->warn(
          "POSE is not served here: hand-eye views are recorded by 'binpick calibrate hand-eye --listen'");
      return refusedReply(Command::Pose, Status::UnknownCommand);
    default: return refusedReply(request.command, Status::UnknownCommand);
  }
}

std::optional<robot::Reply> CellService::State::trigger(robot::ClientId client, const robot::Request& request) {
  const int requested = request.argument ? setup->recipeIndex(*request.argument) : recipe;
  if (stopping || cell_state != CellState::Idle || accepted_trigger) return triggerReply(Status::Busy, 0);
  if (!setup->reconstructor || !setup->config.T_base_camera) {
    core::componentLogger("cell")->warn("TRIGGER refused: {}", setup->reconstructor
                                                                   ? "no hand-eye T_base_camera is configured"
                                                                   : setup->calibration_problem);
    return triggerReply(Status::CalibrationMissing, 0);
  }
  if (requested < 0) return triggerReply(Status::UnknownModel, 0);
  recipe = requested;
  ++cycles_started;  // numbered now: a stop before the capture begins still answers with its number
  accepted_trigger = AcceptedTrigger{setup, recipe};
  trigger_client = client;
  cell_state = CellState::Capturing;
  stage_deadline = Clock::now() + std::chrono::milliseconds(setup->config.limits.capture_timeout_ms);
  stage_expired = false;
  latest.reset();
  cycle_wakeup.notify_one();
  deadline_wakeup.notify_one();
  return std::nullopt;  // answered when the capture is done
}

// FAILED refers to the cycle whose pick the robot received last, whatever the cell does now: a
// robot reports a failed pick when it has tried it, often while the next cycle already computes.
robot::Reply CellService::State::pickFailed(const robot::Request& request) {
  std::optional<int32_t> named = kNoId;  // the argument, else the object of the last pick handed out
  if (request.argument) {
    named = parseObjectId(*request.argument);
  } else if (handed_out) {
    named = handed_out->last_object;
  }
  if (!named) return refusedReply(Command::PickFailed, Status::BadMessage);
  if (!handed_out && last.cycles_done == 0) return failedReply(Status::NoCycle, *named);
  // The detections an object id indexes: those of the cycle whose pick was handed out last, else
  // (none handed out yet) the latest finished cycle's.
  const uint64_t cycle = handed_out ? handed_out->number : last.cycles_done;
  const std::vector<Eigen::Isometry3d>* objects = handed_out ? &handed_out->T_base_objects
                                                  : latest   ? &latest->T_base_objects
                                                             : nullptr;
  if (!objects || *named < 0 || *named >= static_cast<int32_t>(objects->size())) {
    if (!request.argument) {
      core::componentLogger("cell")->warn("FAILED without an object, but no pick was handed out yet");
    } else {
      core::componentLogger("cell")->warn("FAILED names object {}, but cycle {} detected {} objects", *named, cycle,
                                          objects ? objects->size() : 0);
    }
    return refusedReply(Command::PickFailed, Status::BadMessage);
  }
  const uint64_t cycles = avoidFailedPart((*objects)[static_cast<std::size_t>(*named)].translation());
  core::componentLogger("cell")->info("pick of object {} (cycle {}) failed: avoided for {} cycles", *named, cycle,
                                      cycles);
  return failedReply(Status::Ok, *named);
}

void CellService::disconnected(robot::ClientId client) {
  std::lock_guard lock(state_->mutex);
  State& s = *state_;
  // The cycle goes on: a robot that reconnects fetches its picks with NEXT.
  if (s.trigger_client == client) s.trigger_client.reset();
  s.next_waiters.erase(std::remove(s.next_waiters.begin(), s.next_waiters.end(), client), s.next_waiters.end());
}

void CellService::reconfigure(std::shared_ptr<const CellSetup> setup,
                              std::unique_ptr<acquisition::CaptureSource> source) {
  std::lock_guard lock(state_->mutex);
  State& s = *state_;
  const std::string loss = calibrationLoss(*s.setup, *setup);
  if (!loss.empty()) {
    throw core::Error("the new settings are refused: " + loss +
                      "; fix the file and reload again (a restart runs without it)");
  }
  const std::string recipe_name = s.currentRecipe().name;
  s.setup = std::move(setup);
  s.recipe = std::max(0, s.setup->recipeIndex(recipe_name));  // keep the recipe if it still exists
  s.last.recipe = s.currentRecipe().name;
  s.publishSetup(source.get());
  if (source) s.pending_source = std::move(source);
}

std::shared_ptr<const CellReport> CellService::report() const { return state_->board.read(); }

CellSnapshot CellService::snapshot() const {
  std::lock_guard lock(state_->mutex);
  CellSnapshot snapshot = state_->last;
  snapshot.state = state_->cell_state;
  snapshot.recipe = state_->currentRecipe().name;
  return snapshot;
}

bool CellService::healthy() const {
  std::lock_guard lock(state_->mutex);
  if (state_->cell_state == CellState::Idle) return true;
  // Far beyond any deadline: the camera driver or a stage hangs for good.
  return Clock::now() < state_->stage_deadline + std::chrono::seconds(60);
}

}  // namespace binpick::cell
