#pragma once
// A robot of the soak: one connection to binpickd, every request and reply counted in the tally.
// A request whose reply does not come is counted lost and the connection is dropped, so that a
// late reply is never taken for the next request's; the next request connects again.
#include <chrono>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>

#include "daemon_process.hpp"
#include "reply_tally.hpp"

namespace binpick::bench::soak {

class SoakRobot {
 public:
  SoakRobot(int port, ReplyTally& tally, std::string name, std::chrono::milliseconds reply_timeout);
  // The reply, or nullopt when none came (or the daemon could not be reached). A status outside
  // `expected` is counted as unexpected, and the reply returned all the same.
  std::optional<robot::Reply> ask(robot::Command command, std::initializer_list<robot::Status> expected,
                                  const std::string& context = "");
  void leave() { client_.reset(); }

 private:
  bool connect();
  void checkNothingUnasked(const std::string& context);

  int port_;
  ReplyTally& tally_;
  std::string name_;
  std::chrono::milliseconds reply_timeout_;
  std::unique_ptr<cell::testing::RobotClient> client_;
};

}  // namespace binpick::bench::soak
