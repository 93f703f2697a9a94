#pragma once
// What a soak found, and its report: a table for the terminal and docs/benchmark/soak.md.
#include <string>
#include <utility>
#include <vector>

#include "reply_tally.hpp"
#include "soak_reloads.hpp"

namespace binpick::bench::soak {

// binpickd's resident memory (VmRSS, kB), -1 until sampled.
struct MemoryTrack {
  long start = -1;  // serving, before the first cycle
  long warm = -1;   // after the warm-up cycles
  long end = -1;    // after the last cycle
  long max = -1;
  void sample(long kilobytes);
};

// How binpickd ended: stopped by the soak (SIGTERM) or on its own before that.
struct DaemonEnd {
  bool died = false;          // exited or was killed before the soak stopped it
  bool unresponsive = false;  // alive, but stopped answering
  int exit_code = 0;          // as DaemonProcess::wait: -signal when killed by one
  int cycle = 0;              // the cycle during which it died or stopped answering
  std::string last_log_lines;
};

// A kind of warning or error line in the daemon's log (numbers stripped), how often, one example.
struct LogPattern {
  std::string example;
  long count = 0;
};
std::vector<LogPattern> warningsAndErrors(const std::string& log_path);

struct SoakResult {
  std::string command;
  int threads = 1;
  int visitors = 0;
  int reload_every = 0;
  int warmup = 0;
  double minutes = 0.0;
  int cycles_wanted = 0;
  int cycles_run = 0;       // TRIGGER sent
  int cycles_complete = 0;  // TRIGGER ok, then NEXT until no_more_picks
  long picks = 0;
  int min_picks = 0, max_picks = 0;
  std::vector<double> cycle_ms;               // TRIGGER sent to the last NEXT's reply
  std::vector<double> cycle_ms_after_reload;  // the same, of the cycles a reload raced
  MemoryTrack rss;
  TallySummary tally;
  long visits = 0;
  std::vector<ReloadRecord> reloads;
  DaemonEnd daemon;
  std::vector<LogPattern> log_patterns;

  bool passed() const;
};

// The log lines in `result` with this machine's directories named instead (`from` -> `name`), so
// that a report says WORK/calib.yaml, not where the soak happened to run.
void nameDirectories(SoakResult& result, const std::vector<std::pair<std::string, std::string>>& directories);

std::string consoleReport(const SoakResult& result);
std::string markdownReport(const SoakResult& result);

}  // namespace binpick::bench::soak
