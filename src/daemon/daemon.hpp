#pragma once
// binpickd's life: start (settings, prepared models, robot server), serve, reload on SIGHUP, stop
// on SIGTERM, and keep systemd informed (readiness, STATUS= text, watchdog pings).
#include <memory>
#include <string>

namespace binpick::daemon {

struct DaemonOptions {
  std::string config_path;
  int port_override = -1;  // >= 0: listen on this port instead of the settings' (0: any free)
  std::string port_file;   // write the bound port here once listening (scripts, tests)
};

// Blocks SIGTERM, SIGINT and SIGHUP in the calling thread and every thread started after it, so
// that the main loop receives them with sigtimedwait. Call first thing in main.
void blockStopAndReloadSignals();

// Runs until SIGTERM or SIGINT. Returns the exit code; throws core::Error when it cannot start
// (bad settings, a model that cannot be loaded, the port in use).
int runDaemon(const DaemonOptions& options);

}  // namespace binpick::daemon
