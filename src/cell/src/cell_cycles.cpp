// CellService's cycle thread (capture, then the rest of the cycle) and deadline thread.
#include <spdlog/spdlog.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "binpick/acquisition/sequencer.hpp"
#include "binpick/cell/cell_service.hpp"
#include "binpick/core/stopwatch.hpp"
#include "cycle_summary.hpp"
#include "service_logger.hpp"
#include "service_state.hpp"

namespace binpick::cell {
namespace {

using robot::Command;
using robot::Status;

struct CaptureAttempt {
  io::Capture capture;
  Status status = Status::Ok;
  std::string detail;
};

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

// A cycle frees images, clouds and tables of a hundred megabytes and more, allocated on several
// threads (OpenMP workers, the artefact saver): glibc keeps much of that in the threads' arenas
// instead of returning it to the system, and the resident memory creeps up. Trimming after each
// cycle, once its replies are out, hands the free pages back; the next cycle faults its buffers
// in again (docs/binpickd.md, Figures).
void releaseFreedMemory(uint64_t cycle) {
#ifdef __GLIBC__
  const core::Stopwatch trim;
  malloc_trim(0);
  logger()->debug("cycle {}: freed memory returned to the system in {:.1f} ms", cycle, trim.elapsedMs());
#else
  (void)cycle;
#endif
}

}  // namespace

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

void CellService::runCycles() {
  State& s = *state_;
  for (;;) {
    std::unique_lock lock(s.mutex);
    s.cycle_wakeup.wait(lock, [&] { return s.accepted_trigger || s.stopping; });
    if (s.stopping) return;
    // The settings that accepted the TRIGGER, not whatever a reload swapped in since.
    const std::shared_ptr<const CellSetup> setup = std::move(s.accepted_trigger->setup);
    const int recipe_index = s.accepted_trigger->recipe;
    s.accepted_trigger.reset();
    if (s.pending_source) s.source = std::move(s.pending_source);
    const uint64_t cycle = s.cycles_started;  // numbered when its TRIGGER was accepted
    const auto cancel = std::make_shared<core::CancelFlag>();
    s.cycle_cancel = cancel;
    std::vector<Eigen::Vector3d> avoid;
    for (const AvoidEntry& entry : s.avoid) {
      if (entry.from_cycle <= cycle && cycle <= entry.until_cycle) avoid.push_back(entry.centre);
    }
    lock.unlock();

    const core::Stopwatch cycle_time;  // not lapped: the total includes the capture
    CaptureAttempt attempt = captureFrom(s.source.get(), *cancel);
    const double capture_ms = cycle_time.elapsedMs();

    Outbox outbox;
    lock.lock();
    const bool capture_late = s.stage_expired;
    if (!capture_late) {
      if (s.trigger_client) outbox.add(*s.trigger_client, triggerReply(attempt.status, cycle));
      s.trigger_client.reset();
      if (attempt.status != Status::Ok) {
        s.failRunningStage(attempt.status, outbox);
      } else {
        s.cell_state = CellState::Computing;
        s.stage_deadline = Clock::now() + std::chrono::milliseconds(setup->config.limits.processing_timeout_ms);
        s.stage_expired = false;
        s.deadline_wakeup.notify_one();
      }
    }
    const bool go_on = !capture_late && attempt.status == Status::Ok && !s.stopping;
    if (!go_on) s.cell_state = CellState::Idle;  // before the robot hears of it: it may trigger again at once
    s.board.update([&](CellReport& report) {
      CaptureHealth& health = report.capture;
      ++health.captures;
      health.last_capture = std::chrono::system_clock::now();
      health.last_ok = attempt.status == Status::Ok;
      if (!health.last_ok) {
        ++health.failures;
        health.last_error = attempt.detail;
      }
      report.stage = CycleStage::Reconstructing;
    });
    s.publish();
    lock.unlock();
    outbox.send(s.sink);
    if (attempt.status != Status::Ok) logger()->warn("cycle {}: no image: {}", cycle, attempt.detail);
    if (capture_late) logger()->warn("cycle {}: the capture took {:.0f} ms, past its deadline", cycle, capture_ms);

    CycleOutcome outcome;
    if (go_on) {
      const StageObserver on_stage = [&s](CycleStage stage) {
        s.board.update([stage](CellReport& report) { report.stage = stage; });
      };
      outcome = processSafely(*setup, setup->recipes.at(recipe_index), attempt.capture, avoid, *cancel, on_stage);
    } else {
      outcome.status = capture_late ? Status::Timeout : attempt.status;
      outcome.detail = attempt.detail;
    }
    outcome.timing_ms.capture = capture_ms;
    outcome.timing_ms.total = cycle_time.elapsedMs();
    finishCycle(cycle, setup, recipe_index, std::move(attempt.capture), std::move(outcome), go_on);
    if (setup->config.limits.trim_memory_after_cycle) releaseFreedMemory(cycle);
  }
}

void CellService::finishCycle(uint64_t cycle, std::shared_ptr<const CellSetup> setup, int recipe_index,
                              io::Capture capture, CycleOutcome outcome, bool processed) {
  State& s = *state_;
  Outbox outbox;
  bool stopping = false;
  {
    std::lock_guard lock(s.mutex);
    stopping = s.stopping;
    if (processed && s.stage_expired) {
      outcome.status = Status::Timeout;  // its waiters were told at the deadline; the picks are late
      outcome.detail = "the cycle took " + std::to_string(static_cast<int>(outcome.timing_ms.total)) + " ms" +
                       (outcome.detail.empty() ? "" : ": " + outcome.detail);
    } else if (processed) {
      s.latest = LatestCycle{cycle, outcome.status, outcome.picks, outcome.T_base_objects};
      s.answerWaiters(outbox);
    }
    if (processed) s.cell_state = CellState::Idle;  // else the next cycle may already be running
    s.cycle_cancel.reset();
    s.last.cycles_done = cycle;
    s.last.last_status = outcome.status;
    s.last.last_detail = outcome.detail;
    s.last.last_picks = outcome.picks.size();
    s.last.last_parts_detected = outcome.T_base_objects.size();
    s.last.last_timing_ms = outcome.timing_ms;
    s.deadline_wakeup.notify_one();
    // The history first, so that a report naming this cycle as the latest has it. Microseconds: a
    // copy of a few summaries.
    CycleSummary summary = summarizeCycle(cycle, *setup, recipe_index, outcome, std::chrono::system_clock::now());
    s.board.update([&](CellReport& report) { report.recent = withCycle(*report.recent, std::move(summary)); });
    s.publish();
  }
  outbox.send(s.sink);
  const CycleTimings& t = outcome.timing_ms;
  logger()->info("cycle {}: {} ({} picks, {} parts) in {:.0f} ms: capture {:.0f}, reconstruct {:.0f}, detect {:.0f}{}",
                 cycle, robot::statusName(outcome.status), outcome.picks.size(), outcome.T_base_objects.size(), t.total,
                 t.capture, t.reconstruct, t.detect, outcome.detail.empty() ? "" : ": " + outcome.detail);
  for (const std::string& problem : outcome.undeliverable) logger()->error("cycle {}: {}", cycle, problem);
  if (processed) {
    const std::string scene_warning = estimation::sceneWarning(outcome.detection);
    if (!scene_warning.empty()) logger()->warn("cycle {}: {}", cycle, scene_warning);
  }
  if (s.saver && processed && !stopping) {  // a cycle cut short by the stop is not worth the wait
    s.saver->offer(SavedCycle{cycle, std::move(setup), recipe_index, std::move(capture), std::move(outcome)});
  }
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
    logger()->warn("cycle {}: the {} stage missed its deadline", s.cycles_started,
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
