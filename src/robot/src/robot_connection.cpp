#include "binpick/robot/robot_connection.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <thread>

#include "binpick/core/error.hpp"

namespace binpick::robot {
namespace {

using Clock = std::chrono::steady_clock;

int connectOnce(const sockaddr_in& address) {
  const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) throw core::Error(std::string("cannot create a socket: ") + std::strerror(errno));
  if (connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) == 0) {
    const int one = 1;
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof(one));
    return fd;
  }
  close(fd);
  return -1;
}

int remainingMs(Clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return static_cast<int>(std::max<long long>(0, left));
}

}  // namespace

RobotConnection::RobotConnection(const std::string& host, int port, const robot::CodecParams& codec,
                                 std::chrono::milliseconds connect_timeout)
    : codec_(codec), decoder_(codec) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  if (inet_pton(AF_INET, host.c_str(), &address.sin_addr) != 1)
    throw core::Error("'" + host + "' is not an IPv4 address");
  const auto deadline = Clock::now() + connect_timeout;
  while ((fd_ = connectOnce(address)) < 0) {
    if (Clock::now() >= deadline) {
      throw core::Error("cannot connect to " + host + ":" + std::to_string(port) + ": " + std::strerror(errno));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

RobotConnection::~RobotConnection() {
  if (fd_ >= 0) close(fd_);
}

void RobotConnection::sendAll(const std::string& bytes) {
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw core::Error(std::string("cannot send the request: ") + std::strerror(errno));
    sent += static_cast<std::size_t>(n);
  }
}

robot::Reply RobotConnection::request(const robot::Request& request, std::chrono::milliseconds timeout) {
  sendAll(robot::encodeRequest(request, codec_));
  const auto deadline = Clock::now() + timeout;
  for (;;) {
    if (auto reply = decoder_.next()) return *reply;
    pollfd readable{fd_, POLLIN, 0};
    const int ready = poll(&readable, 1, remainingMs(deadline));
    if (ready == 0)
      throw core::Error("no reply to " + std::string(robot::commandKeyword(request.command)) + " within " +
                        std::to_string(timeout.count()) + " ms");
    if (ready < 0 && errno == EINTR) continue;
    char buffer[4096];
    const ssize_t n = recv(fd_, buffer, sizeof(buffer), 0);
    if (n == 0) throw core::Error("binpickd closed the connection");
    if (n < 0) throw core::Error(std::string("cannot read the reply: ") + std::strerror(errno));
    decoder_.feed(buffer, static_cast<std::size_t>(n));
  }
}

}  // namespace binpick::robot
