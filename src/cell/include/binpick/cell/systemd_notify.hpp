#pragma once
// Telling the service manager (systemd, Type=notify) how the daemon is doing: ready, reloading,
// stopping, a one-line status, and watchdog pings. Speaks the notify protocol of sd_notify(3)
// directly, without libsystemd: each call sends one AF_UNIX datagram of "KEY=VALUE" lines to the
// socket named by $NOTIFY_SOCKET.
//
// Thread-safe: every call opens, uses and closes its own socket, so calls from several threads
// (the main loop's status, a watchdog thread's pings) never interfere. Copies share the
// "a failed send was already logged" state.
//
// A notification that cannot be sent (no listener, queue full) is logged once on the "systemd"
// logger, and again only after a send succeeded in between; no call ever throws. A call waits at
// most a second for room in the manager's queue, so a stuck manager cannot stall the daemon.
#include <atomic>
#include <chrono>
#include <cstddef>
#include <memory>
#include <string>

namespace binpick::cell {

class SystemdNotifier {
 public:
  // NOTIFY_SOCKET ("/path" or "@abstract"; unset or empty: disabled), WATCHDOG_USEC (positive
  // microseconds) and WATCHDOG_PID (the watchdog applies only when it is unset or names this
  // process). A garbage WATCHDOG_USEC or WATCHDOG_PID gives no watchdog (logged), never an
  // error. Reads the environment and leaves it unchanged (the daemon starts no children that
  // could mistake the socket for theirs). Throws core::Error naming NOTIFY_SOCKET when it is
  // neither an absolute path nor an "@" name, or longer than a socket address can hold.
  static SystemdNotifier fromEnvironment();

  SystemdNotifier() = default;  // disabled: every call is a no-op
  // `socket_path` as in NOTIFY_SOCKET ("": disabled); `watchdog_interval` 0 for no watchdog.
  // Throws core::Error on a bad path (as above) or a negative interval.
  SystemdNotifier(std::string socket_path, std::chrono::microseconds watchdog_interval);

  bool enabled() const { return !socket_path_.empty(); }
  const std::string& socketPath() const { return socket_path_; }
  // The service manager's watchdog timeout: 0 when there is none. Ping at half of it.
  std::chrono::microseconds watchdogInterval() const { return watchdog_interval_; }

  // Status texts: control characters (newlines included) become spaces, since the protocol is
  // line based; texts longer than kMaxStatusBytes are cut at a UTF-8 character boundary.
  static constexpr std::size_t kMaxStatusBytes = 1024;

  void ready(const std::string& status);  // READY=1, STATUS=
  // RELOADING=1, MONOTONIC_USEC= (CLOCK_MONOTONIC now), STATUS=. Call ready() when the reload
  // is done.
  void reloading(const std::string& status);
  void stopping(const std::string& status);  // STOPPING=1, STATUS=
  void status(const std::string& text);      // STATUS=
  void watchdog();                           // WATCHDOG=1

 private:
  void send(const std::string& message) noexcept;

  std::string socket_path_;
  std::chrono::microseconds watchdog_interval_{0};
  std::shared_ptr<std::atomic<bool>> failure_logged_ = std::make_shared<std::atomic<bool>>(false);
};

}  // namespace binpick::cell
