#include "binpick/cell/systemd_notify.hpp"

#include <time.h>

#include <utility>

#include "binpick/core/component_logger.hpp"
#include "binpick/core/error.hpp"
#include "notify_socket.hpp"

namespace binpick::cell {

namespace {

bool isUtf8Continuation(char byte) { return (static_cast<unsigned char>(byte) & 0xC0) == 0x80; }

// The protocol is one KEY=VALUE per line and the service manager drops datagrams holding NUL
// bytes, so no control character may reach it; a status is one line for `systemctl status`.
std::string statusLine(const std::string& text) {
  std::string line = text;
  for (char& c : line) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7F) c = ' ';
  }
  if (line.size() > SystemdNotifier::kMaxStatusBytes) {
    std::size_t end = SystemdNotifier::kMaxStatusBytes;
    // The service manager ignores a status that is not valid UTF-8: never cut a character.
    while (end > 0 && isUtf8Continuation(line[end])) --end;
    line.resize(end);
  }
  return line;
}

// The service manager compares this with its own clock to tell this reload from a later one.
std::string monotonicMicroseconds() {
  timespec now{};
  ::clock_gettime(CLOCK_MONOTONIC, &now);
  const long long usec = static_cast<long long>(now.tv_sec) * 1000000LL + now.tv_nsec / 1000;
  return std::to_string(usec);
}

}  // namespace

SystemdNotifier::SystemdNotifier(std::string socket_path, std::chrono::microseconds watchdog_interval)
    : socket_path_(std::move(socket_path)), watchdog_interval_(watchdog_interval) {
  if (!socket_path_.empty()) systemd_detail::checkNotifyAddress(socket_path_);
  core::requireField(watchdog_interval.count() >= 0, "systemd notifier", "watchdog_interval", ">= 0 microseconds",
                     watchdog_interval.count());
}

void SystemdNotifier::ready(const std::string& status) { send("READY=1\nSTATUS=" + statusLine(status)); }

void SystemdNotifier::reloading(const std::string& status) {
  send("RELOADING=1\nMONOTONIC_USEC=" + monotonicMicroseconds() + "\nSTATUS=" + statusLine(status));
}

void SystemdNotifier::stopping(const std::string& status) { send("STOPPING=1\nSTATUS=" + statusLine(status)); }

void SystemdNotifier::status(const std::string& text) { send("STATUS=" + statusLine(text)); }

void SystemdNotifier::watchdog() { send("WATCHDOG=1"); }

void SystemdNotifier::send(const std::string& message) noexcept {
  if (!enabled()) return;
  const std::string failure = systemd_detail::sendDatagram(socket_path_, message);
  try {
    if (failure.empty()) {
      if (failure_logged_->exchange(false)) {
        core::componentLogger("systemd")->info("notify socket {} reachable again", socket_path_);
      }
    } else if (!failure_logged_->exchange(true)) {
      // Once per outage: a watchdog ping every few seconds would otherwise flood the journal.
      core::componentLogger("systemd")->warn(
          "cannot notify the service manager at {}: {} (not logged again until a send succeeds)", socket_path_,
          failure);
    }
  } catch (...) {
    // Logging must not turn a lost notification into a crash of the daemon.
  }
}

}  // namespace binpick::cell
