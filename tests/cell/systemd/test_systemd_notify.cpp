// The datagrams a SystemdNotifier sends, byte for byte, to filesystem and abstract sockets.
#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>
#include <time.h>
#include <unistd.h>

#include <chrono>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "binpick/cell/systemd_notify.hpp"
#include "notify_receiver.hpp"
#include "notify_test_fixture.hpp"
#include "thrown_message.hpp"

namespace binpick::test {
namespace {

using cell::SystemdNotifier;
using std::chrono::microseconds;
using SystemdNotify = NotifySocketTest;
using namespace std::string_literals;

long long monotonicMicroseconds() {
  timespec now{};
  ::clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<long long>(now.tv_sec) * 1000000LL + now.tv_nsec / 1000;
}

TEST_F(SystemdNotify, EachCallSendsItsExactDatagram) {
  NotifyReceiver receiver(socketPath());
  SystemdNotifier notifier(socketPath(), microseconds(0));
  ASSERT_TRUE(notifier.enabled());
  notifier.ready("serving robots on port 5000");
  EXPECT_EQ(receiver.next(), "READY=1\nSTATUS=serving robots on port 5000");
  notifier.status("cycle 12: 3 parts");
  EXPECT_EQ(receiver.next(), "STATUS=cycle 12: 3 parts");
  notifier.watchdog();
  EXPECT_EQ(receiver.next(), "WATCHDOG=1");
  notifier.stopping("stopping: SIGTERM");
  EXPECT_EQ(receiver.next(), "STOPPING=1\nSTATUS=stopping: SIGTERM");
  EXPECT_FALSE(receiver.hasPending());
}

TEST_F(SystemdNotify, ReloadingCarriesTheMonotonicClockOfTheCall) {
  NotifyReceiver receiver(socketPath());
  SystemdNotifier notifier(socketPath(), microseconds(0));
  const long long before = monotonicMicroseconds();
  notifier.reloading("reloading the configuration");
  const long long after = monotonicMicroseconds();
  std::istringstream lines(receiver.next().value_or(""));
  std::string reloading, monotonic, status;
  std::getline(lines, reloading);
  std::getline(lines, monotonic);
  std::getline(lines, status);
  EXPECT_EQ(reloading, "RELOADING=1");
  ASSERT_EQ(monotonic.rfind("MONOTONIC_USEC=", 0), 0u) << monotonic;
  const long long usec = std::stoll(monotonic.substr(std::string("MONOTONIC_USEC=").size()));
  EXPECT_GE(usec, before);
  EXPECT_LE(usec, after);
  EXPECT_EQ(status, "STATUS=reloading the configuration");
  EXPECT_TRUE(lines.eof() || lines.peek() == EOF);
}

TEST_F(SystemdNotify, SpeaksToAnAbstractSocket) {
  const std::string name = "@binpick-notify-test-" + std::to_string(::getpid());
  NotifyReceiver receiver(name);
  SystemdNotifier notifier(name, microseconds(0));
  notifier.watchdog();
  EXPECT_EQ(receiver.next(), "WATCHDOG=1");
}

TEST_F(SystemdNotify, StatusBecomesOneLineWithoutControlCharacters) {
  NotifyReceiver receiver(socketPath());
  SystemdNotifier notifier(socketPath(), microseconds(0));
  notifier.status("camera lost\nretrying\r\tin 2 s\0!"s);
  EXPECT_EQ(receiver.next(), "STATUS=camera lost retrying  in 2 s !");
}

TEST_F(SystemdNotify, LongStatusIsCutWithoutSplittingACharacter) {
  NotifyReceiver receiver(socketPath());
  SystemdNotifier notifier(socketPath(), microseconds(0));
  const std::size_t limit = SystemdNotifier::kMaxStatusBytes;
  // "é" is two bytes; placed across the limit it must go entirely.
  notifier.status(std::string(limit - 1, 'a') + "\xC3\xA9" + "tail");
  EXPECT_EQ(receiver.next(), "STATUS=" + std::string(limit - 1, 'a'));
  notifier.status(std::string(limit + 10, 'b'));
  EXPECT_EQ(receiver.next(), "STATUS=" + std::string(limit, 'b'));
}

TEST_F(SystemdNotify, DisabledNotifierSendsNothing) {
  NotifyReceiver receiver(socketPath());
  for (const SystemdNotifier& disabled : {SystemdNotifier(), SystemdNotifier("", microseconds(0))}) {
    SystemdNotifier notifier = disabled;
    EXPECT_FALSE(notifier.enabled());
    EXPECT_EQ(notifier.watchdogInterval(), microseconds(0));
    notifier.ready("x");
    notifier.reloading("x");
    notifier.status("x");
    notifier.watchdog();
    notifier.stopping("x");
  }
  EXPECT_FALSE(receiver.hasPending());
}

TEST_F(SystemdNotify, RejectsAddressesThatAreNoSocketAddress) {
  const microseconds none(0);
  EXPECT_TRUE(throwsNaming([&] { SystemdNotifier("run/notify", none); }, "NOTIFY_SOCKET"));
  EXPECT_TRUE(throwsNaming([&] { SystemdNotifier("@", none); }, "NOTIFY_SOCKET"));
  EXPECT_TRUE(throwsNaming([&] { SystemdNotifier("/" + std::string(120, 'x'), none); }, "NOTIFY_SOCKET"));
  EXPECT_TRUE(throwsNaming([&] { SystemdNotifier(socketPath(), microseconds(-1)); }, "watchdog_interval"));
  EXPECT_EQ(thrownMessage([&] { SystemdNotifier(socketPath(), microseconds(5000000)); }), "");
}

// A test sink in place of the library's logger, to count what a failing socket logs.
class CapturedSystemdLog {
 public:
  CapturedSystemdLog() {
    spdlog::drop("systemd");
    auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(text_);
    spdlog::register_logger(std::make_shared<spdlog::logger>("systemd", sink));
  }
  ~CapturedSystemdLog() { spdlog::drop("systemd"); }
  int count(const std::string& phrase) const {
    const std::string all = text_.str();
    int found = 0;
    for (auto at = all.find(phrase); at != std::string::npos; at = all.find(phrase, at + 1)) ++found;
    return found;
  }

 private:
  std::ostringstream text_;
};

TEST_F(SystemdNotify, FailedSendsNeverThrowAndAreLoggedOncePerOutage) {
  const CapturedSystemdLog log;
  SystemdNotifier notifier(socketPath(), microseconds(0));
  for (int ping = 0; ping < 3; ++ping) EXPECT_NO_THROW(notifier.watchdog());  // nobody listens
  EXPECT_EQ(log.count("cannot notify"), 1);
  {
    NotifyReceiver receiver(socketPath());
    notifier.watchdog();
    EXPECT_EQ(receiver.next(), "WATCHDOG=1");
  }
  EXPECT_EQ(log.count("reachable again"), 1);
  notifier.ready("x");
  notifier.watchdog();
  EXPECT_EQ(log.count("cannot notify"), 2);
}

TEST_F(SystemdNotify, ThreadsSendingAtOnceDeliverEveryDatagramWhole) {
  NotifyReceiver receiver(socketPath());
  SystemdNotifier notifier(socketPath(), microseconds(0));  // one object, shared by all threads
  constexpr int kThreads = 4, kMessages = 25;
  std::vector<std::thread> senders;
  for (int t = 0; t < kThreads; ++t) {
    senders.emplace_back([&notifier, t] {
      for (int m = 0; m < kMessages; ++m)
        notifier.status("thread " + std::to_string(t) + " message " + std::to_string(m));
    });
  }
  std::set<std::string> received;
  for (int i = 0; i < kThreads * kMessages; ++i) received.insert(receiver.next().value_or("(none)"));
  for (std::thread& sender : senders) sender.join();
  std::set<std::string> expected;
  for (int t = 0; t < kThreads; ++t) {
    for (int m = 0; m < kMessages; ++m)
      expected.insert("STATUS=thread " + std::to_string(t) + " message " + std::to_string(m));
  }
  EXPECT_EQ(received, expected);
}

}  // namespace
}  // namespace binpick::test
