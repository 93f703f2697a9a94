// The guided session behind the robot server, until its last view or a stop signal.
#include "hand_eye_guided_serving.hpp"

#include <spdlog/spdlog.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <thread>

#include "binpick/core/error.hpp"
#include "binpick/core/file.hpp"

namespace binpick::cli {
namespace {

// How often the session is looked at while no signal comes.
constexpr std::chrono::milliseconds kTick{100};

// The next stop signal, or 0 after `timeout`.
int waitForStopSignal(std::chrono::milliseconds timeout) {
  const sigset_t signals = stopSignals();
  const timespec wait{0, static_cast<long>(timeout.count()) * 1000000L};
  const int signal = sigtimedwait(&signals, nullptr, &wait);
  return signal > 0 ? signal : 0;
}

// RobotServer::run() on its own thread; stop() (or the destructor) ends it and joins.
class ServingThread {
 public:
  explicit ServingThread(robot::RobotServer& server) : server_(server), thread_([this] { serve(); }) {}
  ~ServingThread() { stop(); }
  ServingThread(const ServingThread&) = delete;
  ServingThread& operator=(const ServingThread&) = delete;

  void stop() {
    server_.stop();
    if (thread_.joinable()) thread_.join();
  }
  bool failed() const { return failed_.load(); }
  const std::string& failure() const { return failure_; }  // once stopped

 private:
  void serve() {
    try {
      server_.run();
    } catch (const std::exception& error) {
      failure_ = error.what();
      failed_.store(true);
    }
  }

  robot::RobotServer& server_;
  std::string failure_;
  std::atomic<bool> failed_{false};
  std::thread thread_;  // last: starts once the members it uses exist
};

}  // namespace

sigset_t stopSignals() {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  return signals;
}

bool serveGuidedSession(const GuidedSessionParams& params, const GuidedServerOptions& options,
                        GuidedViewRecorder& recorder, ViewCamera& camera) {
  // Declared first, destroyed last: the session's thread replies through it until it stops.
  std::unique_ptr<robot::RobotServer> server;
  HandEyeGuidedSession session(params, recorder, camera, [&server](robot::ClientId client, const robot::Reply& reply) {
    server->reply(client, reply);
  });
  server = std::make_unique<robot::RobotServer>(options.server, session);
  ServingThread serving(*server);
  // Atomically: a script polling for it never reads half a number.
  if (!options.port_file.empty()) core::writeFileAtomically(options.port_file, std::to_string(server->port()) + "\n");
  spdlog::info("waiting for the robot on port {} ({}, {}): {} of {} views in {}; images: {}", server->port(),
               options.server.codec.framing == robot::Framing::Ascii ? "ascii" : "binary",
               core::orientationName(options.server.codec.orientation), recorder.accepted(), params.wanted,
               recorder.directory(), camera.description());
  while (!session.finished() && !serving.failed()) {
    if (const int signal = waitForStopSignal(kTick)) {
      spdlog::warn("{}: stopping the session", strsignal(signal));
      break;
    }
  }
  serving.stop();
  session.stop();  // the view being taken is finished and recorded
  if (serving.failed()) throw core::Error("the robot server failed: " + serving.failure());
  return session.complete();
}

}  // namespace binpick::cli
