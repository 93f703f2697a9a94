// SystemdNotifier::fromEnvironment: what the service manager tells the daemon through its
// environment (sd_notify(3), sd_watchdog_enabled(3)).
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <limits>
#include <optional>

#include "binpick/cell/systemd_notify.hpp"
#include "binpick/core/component_logger.hpp"
#include "notify_socket.hpp"

namespace binpick::cell {

namespace {

// A positive decimal number, nothing else (no sign, blanks or suffix); nullopt otherwise.
std::optional<std::int64_t> positiveNumber(const char* text) {
  if (text == nullptr || *text == '\0') return std::nullopt;
  std::int64_t value = 0;
  for (const char* c = text; *c != '\0'; ++c) {
    if (*c < '0' || *c > '9') return std::nullopt;
    const int digit = *c - '0';
    if (value > (std::numeric_limits<std::int64_t>::max() - digit) / 10) return std::nullopt;
    value = value * 10 + digit;
  }
  if (value <= 0) return std::nullopt;
  return value;
}

std::string quoted(const char* text) { return "'" + std::string(text) + "'"; }

// The watchdog applies to this process when WATCHDOG_USEC is valid and WATCHDOG_PID is unset or
// names this process (a child inherits the variables but is not the one being watched).
std::chrono::microseconds watchdogIntervalFromEnvironment() {
  const char* usec_text = std::getenv("WATCHDOG_USEC");
  const char* pid_text = std::getenv("WATCHDOG_PID");
  if (usec_text == nullptr) return std::chrono::microseconds(0);
  const std::optional<std::int64_t> usec = positiveNumber(usec_text);
  if (!usec) {
    core::componentLogger("systemd")->warn(
        "ignoring WATCHDOG_USEC={}: not a positive number of microseconds; no watchdog", quoted(usec_text));
    return std::chrono::microseconds(0);
  }
  if (pid_text != nullptr) {
    const std::optional<std::int64_t> pid = positiveNumber(pid_text);
    if (!pid || *pid != static_cast<std::int64_t>(::getpid())) {
      core::componentLogger("systemd")->info("WATCHDOG_PID={} is not this process; no watchdog", quoted(pid_text));
      return std::chrono::microseconds(0);
    }
  }
  return std::chrono::microseconds(*usec);
}

}  // namespace

SystemdNotifier SystemdNotifier::fromEnvironment() {
  const char* socket = std::getenv("NOTIFY_SOCKET");
  // Without a socket to ping, a watchdog interval would only mislead the caller.
  if (socket == nullptr || *socket == '\0') return SystemdNotifier();
  return SystemdNotifier(socket, watchdogIntervalFromEnvironment());
}

}  // namespace binpick::cell
