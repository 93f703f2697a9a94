#pragma once
// CellService's shared state, guarded by one mutex. Replies are collected while the lock is held
// (Outbox) and sent after it is released, so the server thread never waits on a cycle.
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "artefact_saver.hpp"
#include "binpick/cell/cell_service.hpp"
#include "binpick/core/cancellation.hpp"
#include "cell_replies.hpp"
#include "report_board.hpp"

namespace binpick::cell {

using Clock = std::chrono::steady_clock;

class Outbox {
 public:
  void add(robot::ClientId client, robot::Reply reply) { replies_.emplace_back(client, std::move(reply)); }
  void send(const ReplySink& sink) {
    for (const auto& [client, reply] : replies_) sink(client, reply);
    replies_.clear();
  }

 private:
  std::vector<std::pair<robot::ClientId, robot::Reply>> replies_;
};

// The picks of the latest cycle, handed out one by one.
struct LatestCycle {
  uint64_t number = 0;
  robot::Status status = robot::Status::Ok;
  std::vector<picking::Pick> picks;
  std::vector<Eigen::Isometry3d> T_base_objects;
  std::size_t cursor = 0;
};

// The cycle whose pick the robot received last: what FAILED refers to, whatever the cell does
// meanwhile (a robot reports a failed pick while the next cycle computes).
struct HandedOutCycle {
  uint64_t number = 0;
  std::vector<Eigen::Isometry3d> T_base_objects;
  int last_object = -1;  // the object of the last pick handed out (FAILED without argument)
};

// A TRIGGER the cell accepted: the cycle runs on exactly the settings and recipe that accepted
// it (they were checked to hold a calibration and a hand-eye), whatever a reload swaps in before
// the cycle thread takes it up.
struct AcceptedTrigger {
  std::shared_ptr<const CellSetup> setup;
  int recipe = 0;
};

// A cycle as the cycle thread takes it up: what its TRIGGER fixed, under the lock, before the
// capture begins.
struct StartedCycle {
  uint64_t number = 0;  // numbered when its TRIGGER was accepted
  std::shared_ptr<const CellSetup> setup;
  int recipe = 0;
  std::shared_ptr<core::CancelFlag> cancel;  // also the state's cycle_cancel while it runs
  std::vector<Eigen::Vector3d> avoid;        // the centres of the parts this cycle does not pick
};

// What a capture brought: the images, or why there are none.
struct CaptureAttempt {
  io::Capture capture;
  robot::Status status = robot::Status::Ok;
  std::string detail;
};

// What comes after the capture.
enum class AfterCapture {
  Process,  // the images came in time: reconstruct, detect, plan
  Late,     // the capture deadline has answered the robot already: the cycle ends as a timeout
  End,      // no image, or the service stops: the cycle ends with the capture's status
};

struct AvoidEntry {
  Eigen::Vector3d centre;
  uint64_t from_cycle = 0;   // avoided in cycles numbered from this one (the first not yet numbered)
  uint64_t until_cycle = 0;  // up to this one
  int failures = 1;          // picks of a part at this place that failed, in a row
};

struct CellService::State {
  ReplySink sink;
  mutable std::mutex mutex;
  std::condition_variable cycle_wakeup;
  std::condition_variable deadline_wakeup;

  std::shared_ptr<const CellSetup> setup;
  std::unique_ptr<acquisition::CaptureSource> source;          // used by the cycle thread only
  std::unique_ptr<acquisition::CaptureSource> pending_source;  // from a reload, swapped in between cycles
  int recipe = 0;

  CellState cell_state = CellState::Idle;
  std::optional<AcceptedTrigger> accepted_trigger;  // waiting for the cycle thread
  std::optional<robot::ClientId> trigger_client;    // answered when the capture is done
  std::vector<robot::ClientId> next_waiters;        // NEXT requests waiting for the running cycle
  Clock::time_point stage_deadline;
  bool stage_expired = false;  // the running stage's waiters got "timeout"
  // The running cycle's: set when its result is no longer wanted (deadline, stop), so that it
  // stops computing and the cell is idle again within a fraction of a second.
  std::shared_ptr<core::CancelFlag> cycle_cancel;

  std::optional<LatestCycle> latest;         // reset by TRIGGER: NEXT waits for the new cycle
  std::optional<HandedOutCycle> handed_out;  // kept across cycles: FAILED's reference
  uint64_t cycles_started = 0;               // cycles numbered: each accepted TRIGGER takes the next number
  std::vector<AvoidEntry> avoid;
  CellSnapshot last;  // for snapshot()
  ReportBoard board;  // for report(); has its own locks
  bool stopping = false;

  std::unique_ptr<ArtefactSaver> saver;
  std::thread cycle_thread;
  std::thread deadline_thread;

  // Helpers; the caller holds the mutex.
  const Recipe& currentRecipe() const { return setup->recipes.at(static_cast<std::size_t>(recipe)); }
  // The reply to a request, or nothing for a TRIGGER that started a cycle (answered when the
  // capture is done) and a NEXT that waits for the running cycle.
  std::optional<robot::Reply> answer(robot::ClientId client, const robot::Request& request);
  std::optional<robot::Reply> trigger(robot::ClientId client, const robot::Request& request);
  robot::Reply pickFailed(const robot::Request& request);
  robot::Reply nextPick();  // NEXT from `latest`
  void answerWaiters(Outbox& outbox);
  void failRunningStage(robot::Status status, Outbox& outbox);
  // Publishes the state, recipe, cycle number and waiting picks on the board.
  void publish();
  // Publishes what comes from the settings: recipes, the robot's convention, calibration, source.
  void publishSetup(const acquisition::CaptureSource* new_source);
  // FAILED: avoid the part at `centre` (base frame) in the cycles not yet started; returns for
  // how many.
  uint64_t avoidFailedPart(const Eigen::Vector3d& centre);
  // The centres of the failed parts avoided in cycle `number`.
  std::vector<Eigen::Vector3d> avoidedIn(uint64_t number) const;
  // The capture is in: the TRIGGER's reply, then the processing stage under its deadline, or the
  // cycle's end.
  AfterCapture answerCapture(const StartedCycle& cycle, robot::Status status, Outbox& outbox);
  void startProcessingStage(int timeout_ms);
  // A processed cycle's picks become the latest, for NEXT; its waiters get their replies.
  void handOutPicks(uint64_t number, const CycleOutcome& outcome, Outbox& outbox);
  // The finished cycle for snapshot() and, with the cycle history, on the board.
  void recordOutcome(const StartedCycle& cycle, const CycleOutcome& outcome);

  // The cycle thread's steps (cell_cycles.cpp), in their order; each takes the mutex itself.
  // The next TRIGGER the cell accepted, or nothing once the service stops.
  std::optional<StartedCycle> waitForTrigger();
  void runCycle(const StartedCycle& cycle);
  // Ends the capture stage (answerCapture) and publishes the capture; the robot hears of it
  // after the lock is released.
  AfterCapture endCapture(const StartedCycle& cycle, const CaptureAttempt& attempt);
  CycleOutcome process(const StartedCycle& cycle, const io::Capture& capture);
  // Answers the NEXT requests waiting, records the cycle, logs it and hands it to the artefact
  // saver. `processed`: the cycle got past its capture.
  void finishCycle(const StartedCycle& cycle, io::Capture capture, CycleOutcome outcome, bool processed);
};

}  // namespace binpick::cell
