#pragma once
// The robot's end of a binpickd connection (`binpick robot-client`, the virtual cell's robot): one
// request, one reply, each with a deadline. Used by one thread.
#include <chrono>
#include <string>

#include "binpick/robot/protocol.hpp"

namespace binpick::robot {

class RobotConnection {
 public:
  // Connects, retrying until `connect_timeout` (the daemon may still be starting). Throws
  // core::Error naming the address when it cannot.
  RobotConnection(const std::string& host, int port, const robot::CodecParams& codec,
                  std::chrono::milliseconds connect_timeout);
  ~RobotConnection();
  RobotConnection(const RobotConnection&) = delete;
  RobotConnection& operator=(const RobotConnection&) = delete;

  // Sends the request and waits up to `timeout` for its reply; throws core::Error on a timeout,
  // a closed connection or a malformed reply.
  robot::Reply request(const robot::Request& request, std::chrono::milliseconds timeout);

 private:
  void sendAll(const std::string& bytes);
  int fd_ = -1;
  robot::CodecParams codec_;
  robot::ReplyDecoder decoder_;
};

}  // namespace binpick::robot
