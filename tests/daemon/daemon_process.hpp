#pragma once
// Test support: binpickd as a child process, with a systemd notify socket the test owns, and a
// robot connection over loopback.
#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "binpick/robot/protocol.hpp"

namespace binpick::cell::testing {

// An AF_UNIX datagram socket standing in for systemd's NOTIFY_SOCKET.
class NotifySocket {
 public:
  explicit NotifySocket(const std::string& path);
  ~NotifySocket();
  // The next datagram, or nullopt after `timeout`.
  std::optional<std::string> receive(std::chrono::milliseconds timeout);
  // Reads datagrams until one contains `text`; false after `timeout`.
  bool waitFor(const std::string& text, std::chrono::milliseconds timeout);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
};

struct DaemonOptions {
  std::string config_path;
  std::string port_file;
  std::string notify_socket;  // "" : none
  long watchdog_usec = 0;     // 0 : no watchdog
  std::string stderr_file;    // "" : inherit
};

class DaemonProcess {
 public:
  explicit DaemonProcess(const DaemonOptions& options);
  ~DaemonProcess();  // SIGKILL if still running
  int port(std::chrono::milliseconds timeout = std::chrono::seconds(120));
  void signal(int number) const;
  // The exit code, or nullopt when still running after `timeout` (-signal when killed by one).
  std::optional<int> wait(std::chrono::milliseconds timeout);
  long rssKilobytes() const;  // VmRSS
  int pid() const { return pid_; }

 private:
  DaemonOptions options_;
  int pid_ = -1;
  std::optional<int> exit_code_;
};

// A blocking robot connection with timeouts (a bug fails the test instead of hanging it).
class RobotClient {
 public:
  RobotClient(int port, const robot::CodecParams& codec = {});
  ~RobotClient();
  robot::Reply ask(const robot::Request& request, std::chrono::milliseconds timeout = std::chrono::seconds(120));
  void sendRaw(const std::string& bytes);
  // The next reply; nullopt when the connection closed or nothing came within `timeout`.
  std::optional<robot::Reply> receive(std::chrono::milliseconds timeout);
  void close();

 private:
  int fd_ = -1;
  robot::CodecParams codec_;
  robot::ReplyDecoder decoder_;
};

}  // namespace binpick::cell::testing
