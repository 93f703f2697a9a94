#include "notify_socket.hpp"

#include <sys/socket.h>
#include <sys/time.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstring>

#include "binpick/core/error.hpp"

namespace binpick::cell::systemd_detail {

namespace {

constexpr std::size_t kSunPathBytes = sizeof(sockaddr_un{}.sun_path);
constexpr time_t kSendPatienceSeconds = 1;

// A filesystem path needs its terminating NUL inside sun_path; an abstract name (leading NUL
// instead of '@') is counted by length and needs none.
bool fitsIntoSocketAddress(const std::string& address) {
  return address[0] == '@' ? address.size() <= kSunPathBytes : address.size() < kSunPathBytes;
}

struct SocketAddress {
  sockaddr_un address{};
  socklen_t length = 0;
};

SocketAddress socketAddressOf(const std::string& address) {
  SocketAddress result;
  result.address.sun_family = AF_UNIX;
  std::memcpy(result.address.sun_path, address.data(), address.size());
  const bool abstract = address[0] == '@';
  if (abstract) result.address.sun_path[0] = '\0';
  // The kernel takes an abstract name's length from the address length, so it must not include
  // a terminating NUL; a path is NUL-terminated by the zeroed buffer.
  result.length = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + address.size() + (abstract ? 0 : 1));
  return result;
}

// Owns a descriptor for the duration of one send.
class ScopedDescriptor {
 public:
  explicit ScopedDescriptor(int descriptor) : descriptor_(descriptor) {}
  ~ScopedDescriptor() {
    if (descriptor_ >= 0) ::close(descriptor_);
  }
  ScopedDescriptor(const ScopedDescriptor&) = delete;
  ScopedDescriptor& operator=(const ScopedDescriptor&) = delete;
  int get() const { return descriptor_; }

 private:
  int descriptor_;
};

}  // namespace

void checkNotifyAddress(const std::string& address) {
  const bool absolute_or_abstract = !address.empty() && (address[0] == '/' || address[0] == '@');
  if (!absolute_or_abstract || address.size() < 2 || !fitsIntoSocketAddress(address)) {
    throw core::Error("NOTIFY_SOCKET \"" + address + "\": must be an absolute path or an @abstract name of at most " +
                      std::to_string(kSunPathBytes - 1) + " bytes");
  }
}

std::string sendDatagram(const std::string& address, const std::string& payload) noexcept {
  const ScopedDescriptor socket(::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0));
  if (socket.get() < 0) return std::string("socket(): ") + std::strerror(errno);
  // A full queue (the manager is busy) is waited for, but only so long: a stuck manager must not
  // stall the daemon's pick cycle, whereas a busy one must not lose READY=1 or STOPPING=1.
  const timeval patience{kSendPatienceSeconds, 0};
  ::setsockopt(socket.get(), SOL_SOCKET, SO_SNDTIMEO, &patience, sizeof patience);
  const SocketAddress target = socketAddressOf(address);
  ssize_t sent = -1;
  do {
    sent = ::sendto(socket.get(), payload.data(), payload.size(), MSG_NOSIGNAL,
                    reinterpret_cast<const sockaddr*>(&target.address), target.length);
  } while (sent < 0 && errno == EINTR);
  if (sent < 0) return std::string("sendto(): ") + std::strerror(errno);
  if (static_cast<std::size_t>(sent) != payload.size()) return "sendto(): datagram truncated";
  return "";
}

}  // namespace binpick::cell::systemd_detail
