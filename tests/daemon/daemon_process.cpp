#include "daemon_process.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <fstream>
#include <stdexcept>
#include <thread>

#ifndef BINPICKD_PATH
#error "BINPICKD_PATH must name the binpickd executable"
#endif

namespace binpick::cell::testing {
namespace {

using Clock = std::chrono::steady_clock;

int millisecondsLeft(Clock::time_point deadline) {
  return static_cast<int>(
      std::max<long long>(0, std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count()));
}

bool readable(int fd, Clock::time_point deadline) {
  pollfd p{fd, POLLIN, 0};
  return poll(&p, 1, millisecondsLeft(deadline)) > 0;
}

}  // namespace

NotifySocket::NotifySocket(const std::string& path) : path_(path) {
  fd_ = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::strncpy(address.sun_path, path.c_str(), sizeof(address.sun_path) - 1);
  unlink(path.c_str());
  if (fd_ < 0 || bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) {
    throw std::runtime_error("cannot bind the notify socket " + path);
  }
}

NotifySocket::~NotifySocket() {
  close(fd_);
  unlink(path_.c_str());
}

std::optional<std::string> NotifySocket::receive(std::chrono::milliseconds timeout) {
  if (!readable(fd_, Clock::now() + timeout)) return std::nullopt;
  char buffer[4096];
  const ssize_t n = recv(fd_, buffer, sizeof(buffer), 0);
  return n > 0 ? std::optional<std::string>(std::string(buffer, static_cast<std::size_t>(n))) : std::nullopt;
}

bool NotifySocket::waitFor(const std::string& text, std::chrono::milliseconds timeout) {
  const auto deadline = Clock::now() + timeout;
  while (Clock::now() < deadline) {
    const auto datagram = receive(std::chrono::milliseconds(millisecondsLeft(deadline)));
    if (datagram && datagram->find(text) != std::string::npos) return true;
  }
  return false;
}

DaemonProcess::DaemonProcess(const DaemonOptions& options) : options_(options) {
  unlink(options.port_file.c_str());
  pid_ = fork();
  if (pid_ != 0) return;
  if (!options.notify_socket.empty()) setenv("NOTIFY_SOCKET", options.notify_socket.c_str(), 1);
  if (options.watchdog_usec > 0) {
    setenv("WATCHDOG_USEC", std::to_string(options.watchdog_usec).c_str(), 1);
    setenv("WATCHDOG_PID", std::to_string(getpid()).c_str(), 1);
  }
  // Buffers of 1 MB and more (clouds, images) are mapped and unmapped on their own, so the
  // daemon's RSS follows its live memory: with glibc's default, the mmap threshold rises after the
  // first big free and freed clouds stay resident in whichever thread's arena held them, which
  // made the soak test's leak check depend on how the threads happened to be scheduled.
  setenv("MALLOC_MMAP_THRESHOLD_", "1048576", 1);
  if (!options.stderr_file.empty()) {
    const int fd = open(options.stderr_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 2);
  }
  execl(BINPICKD_PATH, "binpickd", "--config", options.config_path.c_str(), "--port", "0", "--port-file",
        options.port_file.c_str(), static_cast<char*>(nullptr));
  _exit(127);
}

DaemonProcess::~DaemonProcess() {
  if (!exit_code_ && pid_ > 0) {
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
}

int DaemonProcess::port(std::chrono::milliseconds timeout) {
  const auto deadline = Clock::now() + timeout;
  while (Clock::now() < deadline) {
    std::ifstream file(options_.port_file);
    int port = 0;
    if (file >> port && port > 0) return port;
    if (wait(std::chrono::milliseconds(0))) throw std::runtime_error("binpickd exited before listening");
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  throw std::runtime_error("binpickd did not start listening");
}

void DaemonProcess::signal(int number) const { kill(pid_, number); }

std::optional<int> DaemonProcess::wait(std::chrono::milliseconds timeout) {
  const auto deadline = Clock::now() + timeout;
  while (!exit_code_) {
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
      break;
    }
    if (Clock::now() >= deadline) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return exit_code_;
}

long DaemonProcess::rssKilobytes() const {
  std::ifstream status("/proc/" + std::to_string(pid_) + "/status");
  std::string key;
  long value = 0;
  while (status >> key) {
    if (key == "VmRSS:" && status >> value) return value;
  }
  return -1;
}

RobotClient::RobotClient(int port, const robot::CodecParams& codec) : codec_(codec), decoder_(codec) {
  fd_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (connect(fd_, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) {
    throw std::runtime_error("cannot connect to binpickd");
  }
}

RobotClient::~RobotClient() { close(); }

void RobotClient::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

void RobotClient::sendRaw(const std::string& bytes) {
  if (send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL) != static_cast<ssize_t>(bytes.size())) {
    throw std::runtime_error("cannot send to binpickd");
  }
}

std::optional<robot::Reply> RobotClient::receive(std::chrono::milliseconds timeout) {
  const auto deadline = Clock::now() + timeout;
  for (;;) {
    if (auto reply = decoder_.next()) return reply;
    if (!readable(fd_, deadline)) return std::nullopt;
    char buffer[4096];
    const ssize_t n = recv(fd_, buffer, sizeof(buffer), 0);
    if (n <= 0) return std::nullopt;
    decoder_.feed(buffer, static_cast<std::size_t>(n));
  }
}

robot::Reply RobotClient::ask(const robot::Request& request, std::chrono::milliseconds timeout) {
  sendRaw(robot::encodeRequest(request, codec_));
  const auto reply = receive(timeout);
  if (!reply) throw std::runtime_error(std::string("no reply to ") + robot::commandKeyword(request.command));
  return *reply;
}

}  // namespace binpick::cell::testing
