#include "reply_tally.hpp"

namespace binpick::bench::soak {
namespace {

constexpr std::size_t kProblemsKept = 20;  // enough to see a pattern; the counts say how many

std::string describe(const robot::Reply& reply) {
  return std::string(robot::commandKeyword(reply.command)) + " " + robot::statusName(reply.status);
}

}  // namespace

void ReplyTally::sent(robot::Command command) {
  std::lock_guard lock(mutex_);
  ++summary_.sent;
  ++summary_.sent_by_command[robot::commandKeyword(command)];
}

void ReplyTally::answered(robot::Command asked, const robot::Reply& reply, bool expected_status,
                          const std::string& context) {
  std::lock_guard lock(mutex_);
  ++summary_.answered;
  ++summary_.replies_by_command[robot::commandKeyword(asked)][robot::statusName(reply.status)];
  ++summary_.replies_by_status[robot::statusName(reply.status)];
  if (reply.command != asked) {
    ++summary_.mismatched;
    note(context + ": " + robot::commandKeyword(asked) + " answered by " + describe(reply));
  } else if (!expected_status) {
    ++summary_.unexpected;
    note(context + ": " + describe(reply));
  }
}

void ReplyTally::lost(robot::Command asked, const std::string& context) {
  std::lock_guard lock(mutex_);
  ++summary_.lost;
  note(context + ": no reply to " + robot::commandKeyword(asked));
}

void ReplyTally::extra(const robot::Reply& reply, const std::string& context) {
  std::lock_guard lock(mutex_);
  ++summary_.extra;
  note(context + ": a reply nobody asked for: " + describe(reply));
}

void ReplyTally::connectFailed(const std::string& context) {
  std::lock_guard lock(mutex_);
  ++summary_.connect_failures;
  note(context + ": cannot connect");
}

TallySummary ReplyTally::summary() const {
  std::lock_guard lock(mutex_);
  return summary_;
}

void ReplyTally::note(const std::string& problem) {
  if (summary_.problems.size() < kProblemsKept) summary_.problems.push_back(problem);
}

}  // namespace binpick::bench::soak
