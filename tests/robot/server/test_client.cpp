#include "test_client.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cerrno>
#include <exception>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace binpick::test {
namespace {

// Long enough for a loaded machine, short enough that a lost reply fails the test quickly.
constexpr int kTimeoutSeconds = 5;

void setTimeout(int fd, int option) {
  timeval timeout{};
  timeout.tv_sec = kTimeoutSeconds;
  ::setsockopt(fd, SOL_SOCKET, option, &timeout, sizeof timeout);
}

}  // namespace

robot::CodecParams binaryCodec() {
  robot::CodecParams codec;
  codec.framing = robot::Framing::Binary;
  return codec;
}

robot::Request request(robot::Command command, std::optional<std::string> argument) {
  robot::Request result;
  result.command = command;
  result.argument = std::move(argument);
  return result;
}

std::size_t openDescriptorCount() {
  std::size_t count = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator("/proc/self/fd")) {
    ++count;
  }
  return count;
}

namespace {

int portOf(const sockaddr_in& address) { return ntohs(address.sin_port); }

// The local (or, with getpeername, the remote) address of a socket; nothing for other descriptors.
template <typename Get>
std::optional<sockaddr_in> addressOf(int fd, Get get) {
  sockaddr_in address{};
  socklen_t length = sizeof address;
  if (get(fd, reinterpret_cast<sockaddr*>(&address), &length) != 0 || address.sin_family != AF_INET) {
    return std::nullopt;
  }
  return address;
}

}  // namespace

int serverSideSocket(int server_port, int client_port) {
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd")) {
    int fd = -1;
    try {
      fd = std::stoi(entry.path().filename().string());
    } catch (const std::exception&) {
      continue;
    }
    const std::optional<sockaddr_in> local = addressOf(fd, ::getsockname);
    const std::optional<sockaddr_in> remote = addressOf(fd, ::getpeername);
    if (local && remote && portOf(*local) == server_port && portOf(*remote) == client_port) return fd;
  }
  return -1;
}

TestClient::TestClient(int port, const robot::CodecParams& codec, int receive_buffer) : codec_(codec), decoder_(codec) {
  fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throw std::runtime_error("socket failed");
  if (receive_buffer > 0) {
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &receive_buffer, sizeof receive_buffer);
  }
  setTimeout(fd_, SO_RCVTIMEO);
  setTimeout(fd_, SO_SNDTIMEO);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    ::close(fd_);
    throw std::runtime_error("connect failed");
  }
}

TestClient::~TestClient() { close(); }

int TestClient::localPort() const {
  const std::optional<sockaddr_in> local = addressOf(fd_, ::getsockname);
  return local ? portOf(*local) : -1;
}

void TestClient::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

bool TestClient::trySendBytes(const std::string& bytes) {
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    sent += static_cast<std::size_t>(n);
  }
  return true;
}

void TestClient::sendBytes(const std::string& bytes) {
  if (!trySendBytes(bytes)) throw std::runtime_error("send failed");
}

void TestClient::send(const robot::Request& request) { sendBytes(robot::encodeRequest(request, codec_)); }

robot::Reply TestClient::receiveReply() {
  while (true) {
    if (std::optional<robot::Reply> reply = decoder_.next()) return *reply;
    char chunk[512];
    const ssize_t got = ::recv(fd_, chunk, sizeof chunk, 0);
    if (got == 0) throw std::runtime_error("the server closed the connection");
    if (got < 0) throw std::runtime_error("no reply within the receive timeout");
    decoder_.feed(chunk, static_cast<std::size_t>(got));
  }
}

robot::Reply TestClient::roundTrip(const robot::Request& request) {
  send(request);
  return receiveReply();
}

bool TestClient::waitForClose() {
  char chunk[4096];
  while (true) {
    const ssize_t got = ::recv(fd_, chunk, sizeof chunk, 0);
    if (got == 0) return true;
    if (got < 0) return errno == ECONNRESET;
  }
}

}  // namespace binpick::test
