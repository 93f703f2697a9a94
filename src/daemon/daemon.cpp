#include "daemon.hpp"

#include <signal.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <thread>
#include <tuple>

#include "binpick/cell/cell_service.hpp"
#include "binpick/cell/systemd_notify.hpp"
#include "binpick/core/error.hpp"
#include "binpick/core/file.hpp"
#include "binpick/robot/robot_server.hpp"
#include "binpick/web/log_ring.hpp"
#include "binpick/web/web_server.hpp"
#include "status_text.hpp"

namespace binpick::daemon {
namespace {

using namespace binpick::cell;

sigset_t stopAndReloadSignals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGHUP);
  return set;
}

// The next signal, or 0 after `timeout`.
int waitForSignal(std::chrono::milliseconds timeout) {
  const sigset_t set = stopAndReloadSignals();
  timespec wait{static_cast<time_t>(timeout.count() / 1000), static_cast<long>(timeout.count() % 1000) * 1000000L};
  const int signal = sigtimedwait(&set, nullptr, &wait);
  return signal > 0 ? signal : 0;
}

// Whether the robot settings a running server keeps until a restart (its socket, its clients' slots) differ.
bool restartSettingsDiffer(const robot::RobotServerParams& a, const robot::RobotServerParams& b) {
  return std::tie(a.bind_address, a.port, a.max_clients, a.idle_timeout_ms, a.keepalive_idle_s, a.keepalive_interval_s,
                  a.keepalive_count, a.bad_request_log_interval_ms) !=
         std::tie(b.bind_address, b.port, b.max_clients, b.idle_timeout_ms, b.keepalive_idle_s, b.keepalive_interval_s,
                  b.keepalive_count, b.bad_request_log_interval_ms);
}

bool webSettingsDiffer(const std::optional<WebViewConfig>& a, const std::optional<WebViewConfig>& b) {
  if (a.has_value() != b.has_value()) return true;
  if (!a) return false;
  return std::tie(a->bind_address, a->port, a->allowed_clients, a->threads, a->timeout_ms) !=
         std::tie(b->bind_address, b->port, b->allowed_clients, b->threads, b->timeout_ms);
}

// The recent log lines the web view shows, fed by every logger of the process. Installed before
// the cell's threads start (spdlog's sink lists are not guarded).
std::shared_ptr<web::LogRing> recentLogLines(const CellConfig& config) {
  if (!config.web) return nullptr;
  return web::attachLogRing();
}

CellConfig loadConfig(const DaemonOptions& options) {
  CellConfig config = loadCellConfig(options.config_path);
  if (options.port_override >= 0) config.robot.port = options.port_override;
  return config;
}

class Daemon {
 public:
  explicit Daemon(const DaemonOptions& options)
      : options_(options),
        config_(loadConfig(options)),
        log_ring_(recentLogLines(config_)),
        service_(prepareCell(config_), makeCaptureSource(config_.source),
                 [this](robot::ClientId client, const robot::Reply& reply) { server_->reply(client, reply); }),
        server_(std::make_unique<robot::RobotServer>(config_.robot, service_)),
        notifier_(SystemdNotifier::fromEnvironment()) {
    if (config_.web) web_ = std::make_unique<web::WebServer>(*config_.web, webSources());
  }

  int run() {
    std::thread serving([this] { serve(); });
    // Atomically: a script polling for it never reads half a number.
    if (!options_.port_file.empty())
      core::writeFileAtomically(options_.port_file, std::to_string(server_->port()) + "\n");
    spdlog::info("serving robots on {}:{} ({} recipe(s), source: {})", config_.robot.bind_address, server_->port(),
                 config_.recipes.size(), config_.source.mode == SourceConfig::Mode::Replay ? "replay" : "live");
    notifier_.ready(statusText(service_.snapshot(), server_->clientCount()));
    loop();
    notifier_.stopping("stopping");
    stop();
    serving.join();
    spdlog::info("stopped");
    return serve_error_.empty() ? 0 : 1;
  }

 private:
  void serve() {
    try {
      server_->run();
    } catch (const std::exception& e) {  // the listening socket failed: nothing left to serve
      serve_error_ = e.what();
      spdlog::critical("robot server failed: {}", e.what());
      kill(getpid(), SIGTERM);
    }
  }

  // The robots waiting on the cycle are answered (internal_error) while the server still runs;
  // the server writes those replies out before it closes the connections: a robot hears why,
  // never just a closed connection.
  void stop() {
    if (web_) web_->stop();
    service_.stop();  // answers the waiting robots, ends the running cycle
    server_->stop();
  }

  // Signals, watchdog pings and the STATUS= line, until SIGTERM or SIGINT.
  void loop() {
    const auto interval = notifier_.watchdogInterval();
    const auto tick = interval.count() > 0 ? std::chrono::duration_cast<std::chrono::milliseconds>(interval / 2)
                                           : std::chrono::milliseconds(1000);
    std::string last_status;
    for (;;) {
      const int signal = waitForSignal(std::min(tick, std::chrono::milliseconds(1000)));
      if (signal == SIGTERM || signal == SIGINT) return;
      if (signal == SIGHUP) reload();
      if (service_.healthy())
        notifier_.watchdog();
      else
        spdlog::error("a cycle stage hangs far past its deadline; the watchdog will restart the service");
      const std::string status = statusText(service_.snapshot(), server_->clientCount());
      if (status != last_status) notifier_.status(status);
      last_status = status;
    }
  }

  // A bad file keeps the running settings; the robot connections stay up either way.
  void reload() {
    notifier_.reloading("reloading " + options_.config_path);
    try {
      CellConfig config = loadConfig(options_);
      if (webSettingsDiffer(config.web, config_.web)) {
        spdlog::warn("new web view settings take effect at the next restart");
      }
      if (restartSettingsDiffer(config.robot, config_.robot)) {
        spdlog::warn(
            "a new robot bind address, port, max_clients, idle timeout, keepalive or log interval takes effect at the "
            "next restart");
      }
      auto setup = prepareCell(config);
      service_.reconfigure(setup, makeCaptureSource(config.source));
      server_->setCodec(config.robot.codec);
      server_->setAllowedClients(config.robot.allowed_clients);
      config_ = std::move(config);
      spdlog::info("reloaded {}", options_.config_path);
    } catch (const std::exception& e) {
      spdlog::error("reload failed, keeping the running settings: {}", e.what());
    }
    notifier_.ready(statusText(service_.snapshot(), server_->clientCount()));
  }

  // What the web view shows: the cell's published report, the robots, the recent log lines.
  web::WebSources webSources() {
    web::WebSources sources;
    sources.cell = [this] { return service_.report(); };
    sources.robots = [this] { return server_->clients(); };
    sources.log = log_ring_;
    return sources;
  }

  DaemonOptions options_;
  CellConfig config_;
  std::shared_ptr<web::LogRing> log_ring_;
  CellService service_;
  std::unique_ptr<robot::RobotServer> server_;
  SystemdNotifier notifier_;
  std::unique_ptr<web::WebServer> web_;  // last: stopped first, while the cell it shows still exists
  std::string serve_error_;
};

}  // namespace

void blockStopAndReloadSignals() {
  const sigset_t set = stopAndReloadSignals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
}

int runDaemon(const DaemonOptions& options) {
  Daemon daemon(options);
  return daemon.run();
}

}  // namespace binpick::daemon
