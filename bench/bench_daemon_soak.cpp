// bench_daemon_soak: binpickd as it runs for days, in minutes. The real binpickd, on the virtual
// cell's test bin replayed, serves one robot that triggers, fetches picks until none is left and
// triggers again at once, while other robots connect, ask STATUS and PING, report a FAILED pick and
// leave; every few cycles a SIGHUP lands right after the last NEXT, with valid settings and with a
// broken calibration (garbage, a truncated copy, the file removed) in turn, which binpickd must
// refuse while TRIGGER keeps answering ok.
//   bench_daemon_soak [--cycles 1000] [--reload-every 3] [--visitors 2] [--warmup 10] [--threads 1]
//                     [--reply-timeout-s 60] [--work DIR] [--keep] [--out DIR]
// Reports cycles, requests and replies by status (every request must get exactly one), unexpected
// statuses, binpickd's resident memory, cycle times and the reloads with binpickd's verdict on each
// (its log); --out DIR writes DIR/soak.md. Exit 1 when binpickd died or hung, a request went
// without its one reply, a status was unexpected or a reload was not taken or refused as it should.
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "binpick/core/error.hpp"
#include "binpick/core/file.hpp"
#include "binpick/core/stopwatch.hpp"
#include "daemon_soak/reply_tally.hpp"
#include "daemon_soak/soak_cell.hpp"
#include "daemon_soak/soak_reloads.hpp"
#include "daemon_soak/soak_report.hpp"
#include "daemon_soak/soak_robot.hpp"
#include "daemon_soak/soak_visitors.hpp"

namespace binpick::bench::soak {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using robot::Command;
using robot::Status;

constexpr int kUnansweredCyclesBeforeGivingUp = 3;

struct Options {
  int cycles = 1000;
  int reload_every = 3;  // 0: no reloads
  int visitors = 2;
  int warmup = 10;
  int threads = 1;
  int reply_timeout_s = 60;
  std::string work;  // default: a fresh directory under the system's temporary directory, removed after a pass
  bool keep = false;  // keep the default directory after a pass too
  bool work_is_temporary = false;
  std::string out;
};

constexpr const char* kUsage =
    "usage: bench_daemon_soak [--cycles 1000] [--reload-every 3] [--visitors 2] [--warmup 10] [--threads 1]\n"
    "                         [--reply-timeout-s 60] [--work DIR] [--keep] [--out DIR]\n";

int positive(const std::string& key, const std::string& value, int minimum) {
  const int number = std::stoi(value);
  if (number < minimum) throw core::Error(key + " must be >= " + std::to_string(minimum) + " (got " + value + ")");
  return number;
}

Options parseOptions(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string key = argv[i];
    if (key == "--help") {
      std::cout << kUsage;
      std::exit(0);
    }
    if (key == "--keep") {
      options.keep = true;
      continue;
    }
    if (i + 1 >= argc) throw core::Error("option " + key + " needs a value\n" + kUsage);
    const std::string value = argv[++i];
    if (key == "--cycles")
      options.cycles = positive(key, value, 1);
    else if (key == "--reload-every")
      options.reload_every = positive(key, value, 0);
    else if (key == "--visitors")
      options.visitors = positive(key, value, 0);
    else if (key == "--warmup")
      options.warmup = positive(key, value, 0);
    else if (key == "--threads")
      options.threads = positive(key, value, 1);
    else if (key == "--reply-timeout-s")
      options.reply_timeout_s = positive(key, value, 1);
    else if (key == "--work")
      options.work = value;
    else if (key == "--out")
      options.out = value;
    else
      throw core::Error("unknown option " + key + "\n" + kUsage);
  }
  if (options.work.empty()) {
    options.work_is_temporary = true;
    options.work = (fs::temp_directory_path() / ("binpick-soak-" + std::to_string(getpid()))).string();
  }
  return options;
}

struct CycleOutcome {
  bool complete = false;  // TRIGGER ok, then NEXT until no_more_picks
  bool unanswered = false;
  int picks = 0;
  double ms = 0.0;
};

// TRIGGER, then NEXT until no pick is left; timed from the TRIGGER to the last NEXT's reply.
CycleOutcome runCycle(SoakRobot& robot, int cycle) {
  const std::string context = "cycle " + std::to_string(cycle);
  const core::Stopwatch stopwatch;
  CycleOutcome outcome;
  const auto trigger = robot.ask(Command::Trigger, {Status::Ok}, context);
  outcome.unanswered = !trigger;
  if (!trigger || trigger->status != Status::Ok) return outcome;
  for (;;) {
    const auto next = robot.ask(Command::NextPick, {Status::Ok, Status::NoMorePicks}, context);
    if (!next) {
      outcome.unanswered = true;
      return outcome;
    }
    if (next->status != Status::Ok) {
      outcome.complete = next->status == Status::NoMorePicks;
      break;
    }
    ++outcome.picks;
  }
  outcome.ms = stopwatch.elapsedMs();
  return outcome;
}

void record(SoakResult& result, const CycleOutcome& outcome, bool reload_raced) {
  ++result.cycles_run;
  if (!outcome.complete) return;
  result.min_picks = result.cycles_complete == 0 ? outcome.picks : std::min(result.min_picks, outcome.picks);
  result.max_picks = std::max(result.max_picks, outcome.picks);
  ++result.cycles_complete;
  result.picks += outcome.picks;
  result.cycle_ms.push_back(outcome.ms);
  if (reload_raced) result.cycle_ms_after_reload.push_back(outcome.ms);
}

std::string lastLines(const std::string& path, std::size_t count) {
  std::ifstream file(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(file, line);) lines.push_back(line);
  std::string text;
  for (std::size_t i = lines.size() > count ? lines.size() - count : 0; i < lines.size(); ++i) text += lines[i] + "\n";
  return text;
}

// Whether binpickd is gone; if so, how it ended goes into `end`. After a request went unanswered
// it is given a few seconds: a dying process closes its sockets before it can be waited for.
bool daemonDied(SoakCell& cell, DaemonEnd& end, int cycle, bool unanswered) {
  const auto exit_code = cell.daemon().wait(unanswered ? 5s : 0ms);
  if (!exit_code) return false;
  end.died = true;
  end.exit_code = *exit_code;
  end.cycle = cycle;
  return true;
}

void progress(const SoakResult& result, int cycle, const CycleOutcome& outcome, long rss) {
  if (cycle % 50 != 0 && cycle != 1) return;
  std::cout << "cycle " << cycle << ": " << (outcome.complete ? "complete" : "incomplete") << ", " << outcome.picks
            << " picks in " << static_cast<int>(outcome.ms) << " ms, RSS " << rss / 1024 << " MB, "
            << result.tally.sent << " requests so far" << std::endl;
}

// The cycles, with reloads after every `reload_every`-th: the SIGHUP goes right after the last
// NEXT's reply, and the next TRIGGER right after it, so that the reload races the new cycle.
void runCycles(const Options& options, SoakCell& cell, ReplyTally& tally, Reloads& reloads, SoakResult& result) {
  SoakRobot robot(cell.port(), tally, "robot", std::chrono::seconds(options.reply_timeout_s));
  int unanswered_in_a_row = 0;
  bool reload_raced = false;
  for (int cycle = 1; cycle <= options.cycles; ++cycle) {
    const CycleOutcome outcome = runCycle(robot, cycle);
    record(result, outcome, reload_raced);
    const long rss = cell.daemon().rssKilobytes();
    result.rss.sample(rss);
    if (cycle == options.warmup) result.rss.warm = rss;
    result.tally = tally.summary();
    progress(result, cycle, outcome, rss);
    if (daemonDied(cell, result.daemon, cycle, outcome.unanswered)) return;
    unanswered_in_a_row = outcome.unanswered ? unanswered_in_a_row + 1 : 0;
    if (unanswered_in_a_row >= kUnansweredCyclesBeforeGivingUp) {
      result.daemon.unresponsive = true;
      result.daemon.cycle = cycle;
      return;
    }
    reload_raced = options.reload_every > 0 && cycle % options.reload_every == 0 && cycle < options.cycles;
    if (reload_raced) reloads.fire(reloads.nextKind(), cycle);
  }
}

// SIGTERM, as systemd stops it; a daemon that does not go is killed (and said so).
void stopDaemon(SoakCell& cell, SoakResult& result) {
  if (result.daemon.died) return;
  cell.daemon().signal(SIGTERM);
  const auto exit_code = cell.daemon().wait(30s);
  result.daemon.exit_code = exit_code ? *exit_code : -SIGKILL;
}

SoakResult soak(const Options& options, const std::string& command) {
  SoakResult result;
  result.command = command;
  result.threads = options.threads;
  result.visitors = options.visitors;
  result.reload_every = options.reload_every;
  result.warmup = options.warmup;
  result.cycles_wanted = options.cycles;
  const core::Stopwatch stopwatch;

  SoakCell cell(options.work, options.threads);
  cell.start();
  std::cout << "binpickd serving on port " << cell.port() << "; its log: " << cell.logPath() << std::endl;
  result.rss.start = cell.daemon().rssKilobytes();
  ReplyTally tally;
  Reloads reloads(cell);
  {
    Visitors visitors(cell.port(), tally, options.visitors, std::chrono::seconds(options.reply_timeout_s));
    runCycles(options, cell, tally, reloads, result);
    reloads.settle(120s);  // the last reload's verdict; at once when binpickd is gone
    visitors.stop();
    result.visits = visitors.visits();
  }
  stopDaemon(cell, result);
  result.tally = tally.summary();
  result.reloads = reloads.records();
  result.log_patterns = warningsAndErrors(cell.logPath());
  if (result.daemon.died || result.daemon.unresponsive) result.daemon.last_log_lines = lastLines(cell.logPath(), 20);
  nameDirectories(result, {{cell.directory(), "WORK"}, {SoakCell::sceneDirectory(), "SCENE"}});
  result.minutes = stopwatch.elapsedMs() / 60000.0;
  return result;
}

int run(int argc, char** argv) {
  const Options options = parseOptions(argc, argv);
  std::string command = "bench_daemon_soak";
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
  const SoakResult result = soak(options, command);
  std::cout << consoleReport(result);
  if (!options.out.empty()) {
    fs::create_directories(options.out);
    core::writeFileAtomically((fs::path(options.out) / "soak.md").string(), markdownReport(result));
  }
  // A failed soak keeps binpickd's log and settings to look into; a directory the user named is theirs.
  if (result.passed() && !options.keep && options.work_is_temporary)
    fs::remove_all(options.work);
  else
    std::cout << "binpickd's settings and log kept in " << options.work << "\n";
  return result.passed() ? 0 : 1;
}

}  // namespace
}  // namespace binpick::bench::soak

int main(int argc, char** argv) {
  try {
    return binpick::bench::soak::run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "bench_daemon_soak: " << e.what() << "\n";
    return 1;
  }
}
