#pragma once
// Internal: the few POSIX socket calls the server needs, with RAII ownership of descriptors.
// Every descriptor is non-blocking and close-on-exec (a helper process the daemon starts must
// not inherit robot connections). UniqueFd is not thread-safe; the functions are.
#include <netinet/in.h>

#include <string>

namespace binpick::robot::detail {

class UniqueFd {
 public:
  UniqueFd() = default;
  explicit UniqueFd(int fd) : fd_(fd) {}
  ~UniqueFd() { reset(); }
  UniqueFd(UniqueFd&& other) noexcept : fd_(other.release()) {}
  UniqueFd& operator=(UniqueFd&& other) noexcept;
  UniqueFd(const UniqueFd&) = delete;
  UniqueFd& operator=(const UniqueFd&) = delete;

  int get() const { return fd_; }
  bool valid() const { return fd_ >= 0; }
  int release();
  void reset();

 private:
  int fd_ = -1;
};

// A listening TCP socket on address:port (port 0: any free one), SO_REUSEADDR so that a
// restarted daemon can bind while old connections sit in TIME_WAIT. Throws core::Error naming
// the address and port.
UniqueFd listenTcp(const std::string& address, int port);
int boundPort(int socket_fd);

// An eventfd other threads write to wake a poll() on it.
UniqueFd makeEventFd();
void signalEventFd(int fd);
void drainEventFd(int fd);

// Accepts one pending connection; an invalid UniqueFd with errno set when none could be.
UniqueFd acceptClient(int listen_fd, sockaddr_in& peer);
// Requests leave at once instead of waiting for Nagle's algorithm to fill a segment.
void setNoDelay(int fd);
// SO_KEEPALIVE with TCP_KEEPIDLE, TCP_KEEPINTVL and TCP_KEEPCNT: a peer that died without closing
// (power cut, cable pulled) is noticed after idle_s + interval_s * count seconds of silence.
// False with errno set when the kernel refused an option.
bool setKeepAlive(int fd, int idle_s, int interval_s, int count);

std::string errnoText(int error_number);

}  // namespace binpick::robot::detail
