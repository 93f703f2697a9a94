#pragma once
// The soak's reloads: settings and calibration put on disk, SIGHUP, and what binpickd made of it:
// how long until it reported READY=1 again, and whether its log says it took the new settings or
// refused them.
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "soak_cell.hpp"

namespace binpick::bench::soak {

enum class ReloadVerdict { Accepted, Refused, Unknown };

struct ReloadRecord {
  ReloadKind kind = ReloadKind::Valid;
  int after_cycle = 0;
  double ms_to_ready = -1.0;  // -1: READY=1 never came
  ReloadVerdict verdict = ReloadVerdict::Unknown;
  std::string log_line;  // the daemon's line saying so

  // A valid reload must be taken, a broken one refused (the running settings kept).
  bool asExpected() const {
    return verdict == (isBroken(kind) ? ReloadVerdict::Refused : ReloadVerdict::Accepted);
  }
};

class Reloads {
 public:
  explicit Reloads(SoakCell& cell) : cell_(cell) {}
  // Broken and valid in turn, broken first; the broken ones go through garbage, a truncated copy
  // and a removed file.
  ReloadKind nextKind() const;
  // Waits for the previous reload to finish, puts `kind` on disk and sends SIGHUP.
  void fire(ReloadKind kind, int after_cycle);
  // Waits for the reload under way, if any, and reads its verdict from the daemon's log. false
  // when binpickd did not report READY=1 within `timeout` or exited meanwhile.
  bool settle(std::chrono::milliseconds timeout);
  const std::vector<ReloadRecord>& records() const { return records_; }

 private:
  void readVerdict(ReloadRecord& record) const;

  SoakCell& cell_;
  std::vector<ReloadRecord> records_;
  bool pending_ = false;
  std::uintmax_t log_offset_ = 0;  // where the daemon's log stood at the SIGHUP
  NotifyListener::Clock::time_point signalled_;
};

}  // namespace binpick::bench::soak
