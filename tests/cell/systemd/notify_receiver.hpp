#pragma once
// A datagram socket standing in for the service manager's notify socket: the tests point a
// SystemdNotifier at it and read back exactly what was sent.
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstddef>
#include <cstring>
#include <optional>
#include <string>

namespace binpick::test {

class NotifyReceiver {
 public:
  // `address`: a filesystem path, or "@name" for the abstract namespace.
  explicit NotifyReceiver(const std::string& address) : address_(address) {
    descriptor_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    EXPECT_GE(descriptor_, 0) << std::strerror(errno);
    sockaddr_un sun{};
    sun.sun_family = AF_UNIX;
    std::memcpy(sun.sun_path, address.data(), address.size());
    const bool abstract = address[0] == '@';
    if (abstract) sun.sun_path[0] = '\0';
    const auto length = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + address.size() + (abstract ? 0 : 1));
    EXPECT_EQ(::bind(descriptor_, reinterpret_cast<const sockaddr*>(&sun), length), 0)
        << address << ": " << std::strerror(errno);
    // Only so that a test whose datagram never comes fails instead of hanging.
    timeval patience{10, 0};
    ::setsockopt(descriptor_, SOL_SOCKET, SO_RCVTIMEO, &patience, sizeof patience);
  }
  ~NotifyReceiver() {
    if (descriptor_ >= 0) ::close(descriptor_);
    if (address_[0] == '/') ::unlink(address_.c_str());
  }
  NotifyReceiver(const NotifyReceiver&) = delete;
  NotifyReceiver& operator=(const NotifyReceiver&) = delete;

  // The next datagram, or nullopt when none came.
  std::optional<std::string> next() {
    char buffer[8192];
    const ssize_t size = ::recv(descriptor_, buffer, sizeof buffer, 0);
    if (size < 0) return std::nullopt;
    return std::string(buffer, static_cast<std::size_t>(size));
  }
  // Whether a datagram is waiting, without waiting for one.
  bool hasPending() {
    char byte;
    return ::recv(descriptor_, &byte, 1, MSG_DONTWAIT | MSG_PEEK) >= 0;
  }

 private:
  std::string address_;
  int descriptor_ = -1;
};

}  // namespace binpick::test
