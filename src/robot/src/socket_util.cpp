#include "socket_util.hpp"

#include <arpa/inet.h>
#include <netinet/tcp.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>

#include "binpick/core/error.hpp"

namespace binpick::robot::detail {

UniqueFd& UniqueFd::operator=(UniqueFd&& other) noexcept {
  if (this != &other) {
    reset();
    fd_ = other.release();
  }
  return *this;
}

int UniqueFd::release() {
  const int fd = fd_;
  fd_ = -1;
  return fd;
}

void UniqueFd::reset() {
  // No retry on EINTR: on Linux the descriptor is released even then, and a retry could close
  // a descriptor another thread has just been given.
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

std::string errnoText(int error_number) { return std::strerror(error_number); }

UniqueFd listenTcp(const std::string& address, int port) {
  const std::string where = address + ":" + std::to_string(port);
  sockaddr_in socket_address{};
  socket_address.sin_family = AF_INET;
  socket_address.sin_port = htons(static_cast<uint16_t>(port));
  if (inet_pton(AF_INET, address.c_str(), &socket_address.sin_addr) != 1) {
    throw core::Error("cannot listen on " + where + ": not an IPv4 address");
  }
  UniqueFd fd(::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0));
  if (!fd.valid()) throw core::Error("cannot listen on " + where + ": socket: " + errnoText(errno));
  const int on = 1;
  ::setsockopt(fd.get(), SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
  if (::bind(fd.get(), reinterpret_cast<const sockaddr*>(&socket_address), sizeof socket_address) != 0) {
    throw core::Error("cannot listen on " + where + ": " + errnoText(errno));
  }
  if (::listen(fd.get(), SOMAXCONN) != 0) {
    throw core::Error("cannot listen on " + where + ": " + errnoText(errno));
  }
  return fd;
}

int boundPort(int socket_fd) {
  sockaddr_in socket_address{};
  socklen_t length = sizeof socket_address;
  if (::getsockname(socket_fd, reinterpret_cast<sockaddr*>(&socket_address), &length) != 0) {
    throw core::Error("getsockname of the listening socket: " + errnoText(errno));
  }
  return ntohs(socket_address.sin_port);
}

UniqueFd makeEventFd() {
  UniqueFd fd(::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC));
  if (!fd.valid()) throw core::Error("eventfd: " + errnoText(errno));
  return fd;
}

void signalEventFd(int fd) {
  const uint64_t one = 1;
  // EAGAIN means the counter is saturated: the loop is woken anyway, nothing is lost.
  [[maybe_unused]] const ssize_t written = ::write(fd, &one, sizeof one);
}

void drainEventFd(int fd) {
  uint64_t count = 0;
  [[maybe_unused]] const ssize_t got = ::read(fd, &count, sizeof count);
}

UniqueFd acceptClient(int listen_fd, sockaddr_in& peer) {
  socklen_t length = sizeof peer;
  return UniqueFd(::accept4(listen_fd, reinterpret_cast<sockaddr*>(&peer), &length, SOCK_NONBLOCK | SOCK_CLOEXEC));
}

void setNoDelay(int fd) {
  const int on = 1;
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
}

bool setKeepAlive(int fd, int idle_s, int interval_s, int count) {
  const int on = 1;
  return ::setsockopt(fd, SOL_SOCKET, SO_KEEPALIVE, &on, sizeof on) == 0 &&
         ::setsockopt(fd, IPPROTO_TCP, TCP_KEEPIDLE, &idle_s, sizeof idle_s) == 0 &&
         ::setsockopt(fd, IPPROTO_TCP, TCP_KEEPINTVL, &interval_s, sizeof interval_s) == 0 &&
         ::setsockopt(fd, IPPROTO_TCP, TCP_KEEPCNT, &count, sizeof count) == 0;
}

}  // namespace binpick::robot::detail
