// CellService's cycle thread (capture, then the rest of the cycle) and deadline thread.
#include <spdlog/spdlog.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "binpick/acquisition/sequencer.hpp"
#include "binpick/cell/cell_service.hpp"
#include "binpick/core/component_logger.hpp"
#include "binpick/core/stopwatch.hpp"
#include "cycle_summary.hpp"
#include "service_state.hpp"

namespace binpick::cell {
namespace {

using robot::Status;

// A camera fault, a lost frame, an unreadable recording: no image. The source stays usable.
// A capture cancelled at its deadline or by the stop is no image too: its robot was answered.
CaptureAttempt captureFrom(acquisition::CaptureSource* source, const core::CancelFlag& cancel) {
  CaptureAttempt attempt;
  if (!source) {
    attempt.status = Status::NoImage;
    attempt.detail = "no capture source is configured";
    return attempt;
  }
  try {
    attempt.capture = source->next(&cancel);
  } catch (const std::exception& e) {
    attempt.status = Status::NoImage;
    attempt.detail = e.what();
  }
  return attempt;
}

// The capture on the board: its health, and the cycle moves on to reconstruction.
void recordCapture(CellReport& report, const CaptureAttempt& attempt) {
  CaptureHealth& health = report.capture;
  ++health.captures;
  health.last_capture = std::chrono::system_clock::now();
  health.last_ok = attempt.status == Status::Ok;
  if (!health.last_ok) {
    ++health.failures;
    health.last_error = attempt.detail;
  }
  report.stage = CycleStage::Reconstructing;
}

void logCapture(uint64_t cycle, const CaptureAttempt& attempt, AfterCapture next, double capture_ms) {
  if (attempt.status != Status::Ok)
    core::componentLogger("cell")->warn("cycle {}: no image: {}", cycle, attempt.detail);
  if (next == AfterCapture::Late) {
    core::componentLogger("cell")->warn("cycle {}: the capture took {:.0f} ms, past its deadline", cycle, capture_ms);
  }
}

CycleOutcome processSafely(const CellSetup& setup, const Recipe& recipe, const io::Capture& capture,
                           const std::vector<Eigen::Vector3d>& avoid, const core::CancelFlag& cancel,
                           const StageObserver& on_stage) {
  try {
    return processCapture(setup, recipe, capture, avoid, &cancel, on_stage);
  } catch (const core::Cancelled& e) {  // its deadline passed, or the service stops
    CycleOutcome outcome;
    outcome.status = Status::Timeout;
    outcome.detail = std::string("stopped: ") + e.what();
    return outcome;
  } catch (const core::Error& e) {  // a capture the reconstruction refuses: a bad image
    CycleOutcome outcome;
    outcome.status = Status::NoImage;
    outcome.detail = e.what();
    return outcome;
  } catch (const std::exception& e) {
    CycleOutcome outcome;
    outcome.status = Status::InternalError;
    outcome.detail = e.what();
    return outcome;
  }
}

// The outcome of a cycle that ended with its capture.
CycleOutcome unprocessedOutcome(const CaptureAttempt& attempt, AfterCapture next) {
  CycleOutcome outcome;
  outcome.status = next == AfterCapture::Late ? Status::Timeout : attempt.status;
  outcome.detail = attempt.detail;
  return outcome;
}

// A processed cycle finished after the processing deadline: its waiters were told "timeout" at
// the deadline, and its picks are late.
CycleOutcome pastDeadline(CycleOutcome outcome) {
  outcome.status = Status::Timeout;
  outcome.detail = "the cycle took " + std::to_string(static_cast<int>(outcome.timing_ms.total)) + " ms" +
                   (outcome.detail.empty() ? "" : ": " + outcome.detail);
  return outcome;
}

void logOutcome(uint64_t cycle, const CycleOutcome& outcome, bool processed) {
  const auto log = core::componentLogger("cell");
  const CycleTimings& t = outcome.timing_ms;
  log->info("cycle {}: {} ({} picks, {} parts) in {:.0f} ms: capture {:.0f}, reconstruct {:.0f}, detect {:.0f}{}",
            cycle, robot::statusName(outcome.status), outcome.picks.size(), outcome.T_base_objects.size(), t.total,
            t.capture, t.reconstruct, t.detect, outcome.detail.empty() ? "" : ": " + outcome.detail);
  for (const std::string& problem : outcome.undeliverable) log->error("cycle {}: {}", cycle, problem);
  if (processed) {
    const std::string scene_warning = estimation::sceneWarning(outcome.detection);
    if (!scene_warning.empty()) log->warn("cycle {}: {}", cycle, scene_warning);
  }
}

// A cycle frees images, clouds and tables of a hundred megabytes and more, allocated on several
// threads (OpenMP workers, the artefact saver): glibc keeps much of that in the threads' arenas
// instead of returning it to the system, and the resident memory creeps up. Trimming after each
// cycle, once its replies are out, hands the free pages back; the next cycle faults its buffers
// in again (docs/binpickd.md, Figures).
void releaseFreedMemory(uint64_t cycle) {
#ifdef __GLIBC__
  const core::Stopwatch trim;
  malloc_trim(0);
  core::componentLogger("cell")->debug("cycle {}: freed memory returned to the system in {:.1f} ms", cycle,
                                       trim.elapsedMs());
#else
  (void)cycle;
#endif
}

}  // namespace

void CellService::runCycles() {
  while (const std::optional<StartedCycle> cycle = state_->waitForTrigger()) state_->runCycle(*cycle);
}

std::optional<StartedCycle> CellService::State::waitForTrigger() {
  std::unique_lock lock(mutex);
  cycle_wakeup.wait(lock, [&] { return accepted_trigger || stopping; });
  if (stopping) return std::nullopt;
  StartedCycle cycle;
  // The settings that accepted the TRIGGER, not whatever a reload swapped in since.
  cycle.setup = std::move(accepted_trigger->setup);
  cycle.recipe = accepted_trigger->recipe;
  accepted_trigger.reset();
  if (pending_source) source = std::move(pending_source);
  cycle.number = cycles_started;
  cycle.cancel = std::make_shared<core::CancelFlag>();
  cycle_cancel = cycle.cancel;
  cycle.avoid = avoidedIn(cycle.number);
  return cycle;
}

void CellService::State::runCycle(const StartedCycle& cycle) {
  const core::Stopwatch cycle_time;  // not lapped: the total includes the capture
  CaptureAttempt attempt = captureFrom(source.get(), *cycle.cancel);
  const double capture_ms = cycle_time.elapsedMs();
  const AfterCapture next = endCapture(cycle, attempt);
  logCapture(cycle.number, attempt, next, capture_ms);

  const bool processed = next == AfterCapture::Process;
  CycleOutcome outcome = processed ? process(cycle, attempt.capture) : unprocessedOutcome(attempt, next);
  outcome.timing_ms.capture = capture_ms;
  outcome.timing_ms.total = cycle_time.elapsedMs();
  finishCycle(cycle, std::move(attempt.capture), std::move(outcome), processed);
  if (cycle.setup->config.limits.trim_memory_after_cycle) releaseFreedMemory(cycle.number);
}

AfterCapture CellService::State::endCapture(const StartedCycle& cycle, const CaptureAttempt& attempt) {
  Outbox outbox;
  AfterCapture next = AfterCapture::End;
  {
    std::lock_guard lock(mutex);
    next = answerCapture(cycle, attempt.status, outbox);
    board.update([&](CellReport& report) { recordCapture(report, attempt); });
    publish();
  }
  outbox.send(sink);
  return next;
}

CycleOutcome CellService::State::process(const StartedCycle& cycle, const io::Capture& capture) {
  const StageObserver on_stage = [this](CycleStage stage) {
    board.update([stage](CellReport& report) { report.stage = stage; });
  };
  return processSafely(*cycle.setup, cycle.setup->recipes.at(cycle.recipe), capture, cycle.avoid, *cycle.cancel,
                       on_stage);
}

void CellService::State::finishCycle(const StartedCycle& cycle, io::Capture capture, CycleOutcome outcome,
                                     bool processed) {
  Outbox outbox;
  bool stopped = false;
  {
    std::lock_guard lock(mutex);
    stopped = stopping;
    if (processed && stage_expired) {
      outcome = pastDeadline(std::move(outcome));
    } else if (processed) {
      handOutPicks(cycle.number, outcome, outbox);
    }
    if (processed) cell_state = CellState::Idle;  // else the next cycle may already be running
    cycle_cancel.reset();
    deadline_wakeup.notify_one();
    recordOutcome(cycle, outcome);
  }
  outbox.send(sink);
  logOutcome(cycle.number, outcome, processed);
  if (saver && processed && !stopped) {  // a cycle cut short by the stop is not worth the wait
    saver->offer(SavedCycle{cycle.number, cycle.setup, cycle.recipe, std::move(capture), std::move(outcome)});
  }
}

// Helpers; the caller holds the mutex.

void CellService::State::failRunningStage(Status status, Outbox& outbox) {
  if (cycle_cancel) cycle_cancel->cancel();  // nobody waits for its result any more
  if (trigger_client) outbox.add(*trigger_client, triggerReply(status, cycles_started));
  trigger_client.reset();
  latest = LatestCycle{};
  latest->number = cycles_started;
  latest->status = status;
  answerWaiters(outbox);
  stage_expired = true;
}

std::vector<Eigen::Vector3d> CellService::State::avoidedIn(uint64_t number) const {
  std::vector<Eigen::Vector3d> centres;
  for (const AvoidEntry& entry : avoid) {
    if (entry.from_cycle <= number && number <= entry.until_cycle) centres.push_back(entry.centre);
  }
  return centres;
}

AfterCapture CellService::State::answerCapture(const StartedCycle& cycle, Status status, Outbox& outbox) {
  if (stage_expired) {  // its robot got "timeout" at the capture deadline
    cell_state = CellState::Idle;
    return AfterCapture::Late;
  }
  if (trigger_client) outbox.add(*trigger_client, triggerReply(status, cycle.number));
  trigger_client.reset();
  if (status != Status::Ok) {
    failRunningStage(status, outbox);
  } else {
    startProcessingStage(cycle.setup->config.limits.processing_timeout_ms);
  }
  if (status == Status::Ok && !stopping) return AfterCapture::Process;
  cell_state = CellState::Idle;  // before the robot hears of it: it may trigger again at once
  return AfterCapture::End;
}

void CellService::State::startProcessingStage(int timeout_ms) {
  cell_state = CellState::Computing;
  stage_deadline = Clock::now() + std::chrono::milliseconds(timeout_ms);
  stage_expired = false;
  deadline_wakeup.notify_one();
}

void CellService::State::handOutPicks(uint64_t number, const CycleOutcome& outcome, Outbox& outbox) {
  latest = LatestCycle{number, outcome.status, outcome.picks, outcome.T_base_objects};
  answerWaiters(outbox);
}

void CellService::State::recordOutcome(const StartedCycle& cycle, const CycleOutcome& outcome) {
  last.cycles_done = cycle.number;
  last.last_status = outcome.status;
  last.last_detail = outcome.detail;
  last.last_picks = outcome.picks.size();
  last.last_parts_detected = outcome.T_base_objects.size();
  last.last_timing_ms = outcome.timing_ms;
  // The history first, so that a report naming this cycle as the latest has it. Microseconds: a
  // copy of a few summaries.
  CycleSummary summary =
      summarizeCycle(cycle.number, *cycle.setup, cycle.recipe, outcome, std::chrono::system_clock::now());
  board.update([&](CellReport& report) { report.recent = withCycle(*report.recent, std::move(summary)); });
  publish();
}

void CellService::runDeadlines() {
  State& s = *state_;
  std::unique_lock lock(s.mutex);
  while (!s.stopping) {
    const bool armed = s.cell_state != CellState::Idle && !s.stage_expired;
    if (!armed) {
      s.deadline_wakeup.wait(lock);
      continue;
    }
    if (Clock::now() < s.stage_deadline) {
      s.deadline_wakeup.wait_until(lock, s.stage_deadline);
      continue;
    }
    Outbox outbox;
    core::componentLogger("cell")->warn("cycle {}: the {} stage missed its deadline", s.cycles_started,
                                        s.cell_state == CellState::Capturing ? "capture" : "processing");
    s.failRunningStage(Status::Timeout, outbox);
    s.publish();
    lock.unlock();
    outbox.send(s.sink);
    lock.lock();
  }
}

void CellService::stop() {
  State& s = *state_;
  Outbox outbox;
  {
    std::lock_guard lock(s.mutex);
    if (s.stopping) return;
    s.stopping = true;
    if (s.cell_state != CellState::Idle && !s.stage_expired) s.failRunningStage(Status::InternalError, outbox);
    if (s.cycle_cancel) s.cycle_cancel->cancel();  // a stage still running past its deadline too
    s.cycle_wakeup.notify_all();
    s.deadline_wakeup.notify_all();
    s.publish();
  }
  outbox.send(s.sink);
  if (s.cycle_thread.joinable()) s.cycle_thread.join();
  if (s.deadline_thread.joinable()) s.deadline_thread.join();
  s.saver.reset();  // finishes the artefacts being written
}

}  // namespace binpick::cell
