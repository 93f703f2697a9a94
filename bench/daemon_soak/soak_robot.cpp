#include "soak_robot.hpp"

#include <algorithm>

namespace binpick::bench::soak {

using namespace std::chrono_literals;

SoakRobot::SoakRobot(int port, ReplyTally& tally, std::string name, std::chrono::milliseconds reply_timeout)
    : port_(port), tally_(tally), name_(std::move(name)), reply_timeout_(reply_timeout) {}

bool SoakRobot::connect() {
  if (client_) return true;
  try {
    client_ = std::make_unique<cell::testing::RobotClient>(port_);
    return true;
  } catch (const std::exception&) {
    tally_.connectFailed(name_);
    return false;
  }
}

// Between requests nothing may be waiting: a reply here answers no request of ours.
void SoakRobot::checkNothingUnasked(const std::string& context) {
  while (const auto unasked = client_->receive(0ms)) tally_.extra(*unasked, context);
}

std::optional<robot::Reply> SoakRobot::ask(robot::Command command, std::initializer_list<robot::Status> expected,
                                           const std::string& context) {
  if (!connect()) return std::nullopt;
  const std::string where = context.empty() ? name_ : name_ + ", " + context;
  checkNothingUnasked(where);
  tally_.sent(command);
  std::optional<robot::Reply> reply;
  try {
    client_->sendRaw(robot::encodeRequest(robot::Request{command}, {}));
    reply = client_->receive(reply_timeout_);
  } catch (const std::exception&) {
    // the connection broke while sending: no reply will come
  }
  if (!reply) {
    tally_.lost(command, where);
    client_.reset();
    return std::nullopt;
  }
  const bool wanted = std::find(expected.begin(), expected.end(), reply->status) != expected.end();
  tally_.answered(command, *reply, wanted, where);
  return reply;
}

}  // namespace binpick::bench::soak
