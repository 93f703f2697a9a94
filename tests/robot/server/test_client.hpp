#pragma once
// A robot controller for the server tests: a blocking socket with send and receive timeouts, so
// that a server bug fails a test instead of hanging it. Not thread-safe: one per thread.
#include <cstddef>
#include <optional>
#include <string>

#include "binpick/robot/protocol.hpp"

namespace binpick::test {

robot::CodecParams binaryCodec();
robot::Request request(robot::Command command, std::optional<std::string> argument = {});
std::size_t openDescriptorCount();  // of this process
// The server's end of the connection from loopback port `client_port` to `server_port`, found
// among this process's descriptors (the servers under test run in it); -1 when there is none.
int serverSideSocket(int server_port, int client_port);

class TestClient {
 public:
  // receive_buffer > 0 shrinks the socket's receive buffer (a client that reads slowly).
  explicit TestClient(int port, const robot::CodecParams& codec = {}, int receive_buffer = 0);
  ~TestClient();
  TestClient(const TestClient&) = delete;
  TestClient& operator=(const TestClient&) = delete;

  void sendBytes(const std::string& bytes);     // throws std::runtime_error when it cannot
  bool trySendBytes(const std::string& bytes);  // false once the server has dropped us
  void send(const robot::Request& request);
  robot::Reply receiveReply();  // throws on timeout, close or a bad reply
  robot::Reply roundTrip(const robot::Request& request);
  // Reads and discards until the server closes (true) or nothing arrives for the timeout.
  bool waitForClose();
  void close();
  int localPort() const;

 private:
  int fd_ = -1;
  robot::CodecParams codec_;
  robot::ReplyDecoder decoder_;
};

}  // namespace binpick::test
