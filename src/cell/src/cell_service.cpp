// CellService: the robot's requests. Runs on the server thread: never blocks beyond the lock.
#include "binpick/cell/cell_service.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "service_logger.hpp"
#include "service_state.hpp"

namespace binpick::cell {
namespace {

using robot::Command;
using robot::Reply;
using robot::Status;

Reply reply(Command command, Status status, std::vector<int32_t> integers = {}) {
  Reply r;
  r.command = command;
  r.status = status;
  r.integers = std::move(integers);
  return r;
}

std::optional<int> parseIndex(const std::string& text) {
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos) {
    return std::nullopt;
  }
  return std::stoi(text);
}

constexpr uint64_t kForgetCycles = 200;  // a failed place not failed again for this long is forgotten
constexpr int kMaxDoublings = 6;         // avoided at most 64 x limits.avoid_cycles

}  // namespace

// A part whose pick failed is avoided for limits.avoid_cycles cycles; each further failure at the
// same place (within the recipe's avoid_radius of an earlier one) doubles that, so that a part the
// robot cannot hold stops being offered instead of failing every few cycles.
uint64_t CellService::State::avoidFailedPart(const Eigen::Vector3d& centre) {
  const uint64_t now = latest->number;
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
  avoid.push_back({centre, now + cycles, failures});
  return cycles;
}

robot::Reply CellService::State::nextPick() {
  if (latest->status != Status::Ok) return reply(Command::NextPick, latest->status, {0});
  if (latest->cursor >= latest->picks.size()) return reply(Command::NextPick, Status::NoMorePicks, {0});
  const picking::Pick& pick = latest->picks[latest->cursor++];
  latest->last_object = pick.object;
  const auto remaining = static_cast<int32_t>(latest->picks.size() - latest->cursor);
  Reply r = reply(Command::NextPick, Status::Ok, {remaining, pick.object, pick.grasp});
  r.T_base_tool = pick.T_base_grasp;
  return r;
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
  state_->cycle_thread = std::thread([this] { runCycles(); });
  state_->deadline_thread = std::thread([this] { runDeadlines(); });
}

CellService::~CellService() { stop(); }

void CellService::handle(robot::ClientId client, const robot::Request& request) {
  Outbox outbox;
  {
    std::lock_guard lock(state_->mutex);
    State& s = *state_;
    const std::string argument = request.argument.value_or("");
    switch (request.command) {
      case Command::Ping: outbox.add(client, reply(Command::Ping, Status::Ok)); break;
      case Command::Status:
        outbox.add(client, reply(Command::Status, Status::Ok,
                                 {static_cast<int32_t>(s.cell_state), s.recipe, clampToInt32(s.last.cycles_done)}));
        break;
      case Command::SelectModel: {
        const int index = s.setup->recipeIndex(argument);
        if (index >= 0) s.recipe = index;
        outbox.add(client, index >= 0 ? reply(Command::SelectModel, Status::Ok, {index})
                                      : reply(Command::SelectModel, Status::UnknownModel));
        break;
      }
      case Command::Trigger: {
        const int requested = request.argument ? s.setup->recipeIndex(argument) : s.recipe;
        if (s.stopping || s.cell_state != CellState::Idle || s.trigger_requested) {
          outbox.add(client, reply(Command::Trigger, Status::Busy));
        } else if (!s.setup->reconstructor || !s.setup->config.T_base_camera) {
          logger()->warn("TRIGGER refused: {}", s.setup->reconstructor ? "no hand-eye T_base_camera is configured"
                                                                       : s.setup->calibration_problem);
          outbox.add(client, reply(Command::Trigger, Status::CalibrationMissing));
        } else if (requested < 0) {
          outbox.add(client, reply(Command::Trigger, Status::UnknownModel));
        } else {
          s.recipe = requested;
          s.trigger_requested = true;
          s.trigger_client = client;
          s.cell_state = CellState::Capturing;
          s.stage_deadline = Clock::now() + std::chrono::milliseconds(s.setup->config.limits.capture_timeout_ms);
          s.stage_expired = false;
          s.latest.reset();
          s.cycle_wakeup.notify_one();
          s.deadline_wakeup.notify_one();
        }
        break;
      }
      case Command::NextPick:
        if (s.latest)
          outbox.add(client, s.nextPick());
        else if (s.cell_state != CellState::Idle)
          s.next_waiters.push_back(client);
        else
          outbox.add(client, reply(Command::NextPick, Status::NoCycle, {0}));
        break;
      case Command::PickFailed: {
        if (!s.latest) {
          outbox.add(client, reply(Command::PickFailed, Status::NoCycle));
          break;
        }
        const std::optional<int> object =
            request.argument ? parseIndex(argument) : std::optional<int>(s.latest->last_object);
        if (!object || *object < 0 || *object >= static_cast<int>(s.latest->T_base_objects.size())) {
          outbox.add(client, reply(Command::PickFailed, Status::BadMessage));
          break;
        }
        const uint64_t cycles = s.avoidFailedPart(s.latest->T_base_objects[*object].translation());
        logger()->info("pick of object {} (cycle {}) failed: avoided for {} cycles", *object, s.latest->number, cycles);
        outbox.add(client, reply(Command::PickFailed, Status::Ok, {*object}));
        break;
      }
      case Command::Pose:
        // Hand-eye views are recorded by the calibration tool; a robot sending them here is
        // talking to the wrong program, and the log says which one it wants.
        logger()->warn("POSE is not served here: hand-eye views are recorded by 'binpick calibrate hand-eye --listen'");
        outbox.add(client, reply(Command::Pose, Status::UnknownCommand));
        break;
      default: outbox.add(client, reply(request.command, Status::UnknownCommand));
    }
  }
  outbox.send(state_->sink);
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
  const std::string recipe_name = s.currentRecipe().name;
  s.setup = std::move(setup);
  s.recipe = std::max(0, s.setup->recipeIndex(recipe_name));  // keep the recipe if it still exists
  s.last.recipe = s.currentRecipe().name;
  if (source) s.pending_source = std::move(source);
}

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
