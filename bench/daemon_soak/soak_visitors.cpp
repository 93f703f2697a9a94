#include "soak_visitors.hpp"

#include <random>
#include <string>

#include "soak_robot.hpp"

namespace binpick::bench::soak {
namespace {

using namespace std::chrono_literals;
using robot::Command;
using robot::Status;

}  // namespace

Visitors::Visitors(int port, ReplyTally& tally, int count, std::chrono::milliseconds reply_timeout)
    : port_(port), tally_(tally), reply_timeout_(reply_timeout) {
  for (int i = 0; i < count; ++i) threads_.emplace_back([this, i] { visitAgainAndAgain(i + 1); });
}

void Visitors::stop() {
  stopping_ = true;
  for (std::thread& thread : threads_) {
    if (thread.joinable()) thread.join();
  }
}

void Visitors::visitAgainAndAgain(int index) {
  std::mt19937 random(static_cast<unsigned>(index));
  const std::string name = "visitor " + std::to_string(index);
  while (!stopping_) {
    SoakRobot visitor(port_, tally_, name, reply_timeout_);
    visitor.ask(Command::Status, {Status::Ok});
    visitor.ask(Command::Ping, {Status::Ok});
    // FAILED names the last pick handed out: bad_message before the cycle's first pick, no_cycle
    // before any cycle.
    if (random() % 4 == 0) visitor.ask(Command::PickFailed, {Status::Ok, Status::BadMessage, Status::NoCycle});
    visitor.leave();
    ++visits_;
    pause(std::chrono::milliseconds(100 + random() % 400));
  }
}

// Short slices, so that stop() does not wait out a whole pause.
void Visitors::pause(std::chrono::milliseconds duration) const {
  for (auto slept = 0ms; slept < duration && !stopping_; slept += 10ms) std::this_thread::sleep_for(10ms);
}

}  // namespace binpick::bench::soak
