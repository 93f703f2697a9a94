#pragma once
// Every request the soak's robots send and what came back: replies by command and status, and the
// ones that break the protocol's promise of exactly one reply per request, in order (no reply, a
// reply to another command, a reply nobody asked for) or carry a status the soak did not expect.
// Thread-safe: the robots share one.
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "binpick/robot/protocol.hpp"

namespace binpick::bench::soak {

struct TallySummary {
  long sent = 0;
  long answered = 0;
  long lost = 0;        // no reply within the timeout, or the connection closed first
  long mismatched = 0;  // the reply named another command
  long extra = 0;       // a reply with no request outstanding
  long unexpected = 0;  // answered, with a status the request should not get
  long connect_failures = 0;
  std::map<std::string, long> sent_by_command;
  std::map<std::string, std::map<std::string, long>> replies_by_command;  // command -> status -> count
  std::map<std::string, long> replies_by_status;
  std::vector<std::string> problems;  // the first few, described

  bool everyRequestAnsweredOnce() const { return lost == 0 && mismatched == 0 && extra == 0; }
};

class ReplyTally {
 public:
  void sent(robot::Command command);
  void answered(robot::Command asked, const robot::Reply& reply, bool expected_status, const std::string& context);
  void lost(robot::Command asked, const std::string& context);
  void extra(const robot::Reply& reply, const std::string& context);
  void connectFailed(const std::string& context);
  TallySummary summary() const;

 private:
  void note(const std::string& problem);  // with the mutex held

  mutable std::mutex mutex_;
  TallySummary summary_;
};

}  // namespace binpick::bench::soak
