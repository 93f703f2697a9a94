// SystemdNotifier::fromEnvironment: the variables the service manager sets, valid and garbage.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <chrono>
#include <optional>
#include <string>

#include "binpick/cell/systemd_notify.hpp"
#include "notify_receiver.hpp"
#include "notify_test_fixture.hpp"
#include "thrown_message.hpp"

namespace binpick::test {
namespace {

using cell::SystemdNotifier;
using std::chrono::microseconds;

// Sets (or, with nullopt, unsets) an environment variable for one test and restores it after.
class ScopedVariable {
 public:
  ScopedVariable(const char* name, const std::optional<std::string>& value) : name_(name) {
    if (const char* old = ::getenv(name)) old_ = old;
    value ? ::setenv(name, value->c_str(), 1) : ::unsetenv(name);
  }
  ~ScopedVariable() { old_ ? ::setenv(name_, old_->c_str(), 1) : ::unsetenv(name_); }
  ScopedVariable(const ScopedVariable&) = delete;
  ScopedVariable& operator=(const ScopedVariable&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// The three variables the service manager passes, set together.
struct ServiceEnvironment {
  ServiceEnvironment(const std::optional<std::string>& socket, const std::optional<std::string>& usec,
                     const std::optional<std::string>& pid)
      : socket_("NOTIFY_SOCKET", socket), usec_("WATCHDOG_USEC", usec), pid_("WATCHDOG_PID", pid) {}
  ScopedVariable socket_, usec_, pid_;
};

std::string ourPid() { return std::to_string(::getpid()); }

using SystemdEnvironment = NotifySocketTest;

TEST_F(SystemdEnvironment, WithoutNotifySocketEverythingIsDisabled) {
  for (const std::optional<std::string>& socket : {std::optional<std::string>(), std::optional<std::string>("")}) {
    const ServiceEnvironment environment(socket, "10000000", ourPid());
    const SystemdNotifier notifier = SystemdNotifier::fromEnvironment();
    EXPECT_FALSE(notifier.enabled());
    EXPECT_EQ(notifier.watchdogInterval(), microseconds(0));  // nowhere to ping
  }
}

TEST_F(SystemdEnvironment, ReadsTheSocketAndTheWatchdogMeantForThisProcess) {
  NotifyReceiver receiver(socketPath());
  const ServiceEnvironment environment(socketPath(), "10000000", ourPid());
  SystemdNotifier notifier = SystemdNotifier::fromEnvironment();
  EXPECT_TRUE(notifier.enabled());
  EXPECT_EQ(notifier.socketPath(), socketPath());
  EXPECT_EQ(notifier.watchdogInterval(), microseconds(10000000));
  notifier.ready("up");
  EXPECT_EQ(receiver.next(), "READY=1\nSTATUS=up");
}

TEST_F(SystemdEnvironment, WatchdogWithoutPidAppliesToThisProcess) {
  const ServiceEnvironment environment("@binpick-env-test", "2500000", std::nullopt);
  EXPECT_EQ(SystemdNotifier::fromEnvironment().watchdogInterval(), microseconds(2500000));
}

TEST_F(SystemdEnvironment, WatchdogOfAnotherProcessIsNotOurs) {
  const std::string other = std::to_string(::getpid() + 1);
  for (const std::string& pid : {other, std::string("1"), std::string("garbage"), std::string("")}) {
    const ServiceEnvironment environment(socketPath(), "10000000", pid);
    const SystemdNotifier notifier = SystemdNotifier::fromEnvironment();
    EXPECT_TRUE(notifier.enabled()) << pid;
    EXPECT_EQ(notifier.watchdogInterval(), microseconds(0)) << "WATCHDOG_PID=" << pid;
  }
}

TEST_F(SystemdEnvironment, GarbageWatchdogUsecMeansNoWatchdog) {
  for (const char* usec : {"", "abc", "-5", "0", "12x", " 100", "1e6", "99999999999999999999999"}) {
    const ServiceEnvironment environment(socketPath(), std::string(usec), ourPid());
    SystemdNotifier notifier;
    EXPECT_NO_THROW(notifier = SystemdNotifier::fromEnvironment()) << usec;
    EXPECT_TRUE(notifier.enabled()) << usec;
    EXPECT_EQ(notifier.watchdogInterval(), microseconds(0)) << "WATCHDOG_USEC=" << usec;
  }
}

TEST_F(SystemdEnvironment, ARelativeNotifySocketIsAnErrorNamingIt) {
  const ServiceEnvironment environment("run/systemd/notify", std::nullopt, std::nullopt);
  EXPECT_TRUE(throwsNaming([] { SystemdNotifier::fromEnvironment(); }, "NOTIFY_SOCKET \"run/systemd/notify\""));
}

}  // namespace
}  // namespace binpick::test
