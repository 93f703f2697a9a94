#pragma once
// The cell's request handling behind the robot server: one pick cycle at a time (capture ->
// reconstruct -> detect -> plan), requests answered without ever blocking the server thread, and
// every stage under a deadline (a cycle past it is cancelled), so that the robot always gets an
// answer, in one reply shape per command (docs/robot-protocol.md, "Reply shapes"):
//   TRIGGER  answered when the capture is done (the robot may move away while the cycle computes),
//            or "busy", "calibration missing", "no image", "timeout" at the capture deadline.
//   NEXT     the next pick of the latest cycle, waiting for the cycle if it is still computing (up
//            to the processing deadline); the cycle's status when it found nothing to pick.
//   FAILED   the object is avoided in the next limits.avoid_cycles cycles.
//   MODEL    the recipe of the next cycles;  STATUS, PING.
// Threads: the cycle runs on its own thread, deadlines on another, saved artefacts on a third.
// handle(), disconnected(), reconfigure(), snapshot(), report() and healthy() are thread-safe.
#include <chrono>
#include <functional>
#include <memory>
#include <string>

#include "binpick/cell/cell_report.hpp"
#include "binpick/cell/cell_setup.hpp"
#include "binpick/cell/pick_cycle.hpp"
#include "binpick/robot/robot_server.hpp"

namespace binpick::cell {

using ReplySink = std::function<void(robot::ClientId, const robot::Reply&)>;

struct CellSnapshot {
  CellState state = CellState::Idle;
  std::string recipe;
  uint64_t cycles_done = 0;
  robot::Status last_status = robot::Status::Ok;
  std::string last_detail;
  std::size_t last_picks = 0;
  std::size_t last_parts_detected = 0;
  CycleTimings last_timing_ms;
};

class CellService : public robot::RequestHandler {
 public:
  // `sink` sends a reply to a client (RobotServer::reply); it is called without locks held.
  CellService(std::shared_ptr<const CellSetup> setup, std::unique_ptr<acquisition::CaptureSource> source,
              ReplySink sink);
  ~CellService() override;  // stop()
  CellService(const CellService&) = delete;
  CellService& operator=(const CellService&) = delete;

  void handle(robot::ClientId client, const robot::Request& request) override;
  void disconnected(robot::ClientId client) override;

  // A reloaded configuration: a cycle whose TRIGGER was accepted runs on the settings that
  // accepted it, the next uses the new ones. `source` null: keep the current capture source.
  // Throws core::Error, changing nothing, when the new settings would lose a rig calibration or a
  // hand-eye the running ones have (calibrationLoss).
  void reconfigure(std::shared_ptr<const CellSetup> setup, std::unique_ptr<acquisition::CaptureSource> source);
  // Answers every waiting robot ("internal error": the service is stopping) through the sink, so
  // call it while the server still sends replies; cancels the running cycle (a capture under way
  // is waited for), finishes the artefact being saved and joins the threads. Idempotent.
  void stop();

  CellSnapshot snapshot() const;
  // The state as published at its last change, for observers (the web view). Never waits for the
  // cycle: it copies a pointer under a lock of its own.
  std::shared_ptr<const CellReport> report() const;
  // False once a stage has overrun its deadline by far more than any camera timeout (a hung
  // driver): the daemon then stops feeding systemd's watchdog, which restarts the service.
  bool healthy() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
  void runCycles();
  void runDeadlines();
};

}  // namespace binpick::cell
