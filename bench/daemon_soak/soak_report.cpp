#include "soak_report.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <map>
#include <thread>
#include <utility>

namespace binpick::bench::soak {
namespace {

using Rows = std::vector<std::pair<std::string, std::string>>;

constexpr std::size_t kLogPatternsShown = 15;
constexpr std::size_t kReloadProblemsShown = 10;

template <typename... Args>
std::string format(const char* pattern, Args... args) {
  char text[512];
  std::snprintf(text, sizeof(text), pattern, args...);
  return text;
}

double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double at = q * static_cast<double>(values.size() - 1);
  const std::size_t below = static_cast<std::size_t>(at);
  const std::size_t above = std::min(below + 1, values.size() - 1);
  return values[below] + (at - static_cast<double>(below)) * (values[above] - values[below]);
}

std::string seconds(const std::vector<double>& ms) {
  if (ms.empty()) return "none";
  return format("median %.2f s, p95 %.2f s, max %.2f s (%zu cycles)", quantile(ms, 0.5) / 1000.0,
                quantile(ms, 0.95) / 1000.0, quantile(ms, 1.0) / 1000.0, ms.size());
}

std::string megabytes(long kilobytes) { return kilobytes < 0 ? "-" : format("%.0f MB", kilobytes / 1024.0); }

std::string countsText(const std::map<std::string, long>& counts) {
  std::vector<std::pair<std::string, long>> sorted(counts.begin(), counts.end());
  std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  std::string text;
  for (const auto& [name, count] : sorted) text += (text.empty() ? "" : ", ") + name + " " + std::to_string(count);
  return text.empty() ? "none" : text;
}

std::string exitText(int exit_code) {
  if (exit_code >= 0) return "exit code " + std::to_string(exit_code);
  return format("killed by signal %d (%s)", -exit_code, strsignal(-exit_code));
}

std::string daemonText(const DaemonEnd& end) {
  if (end.died) return "died during cycle " + std::to_string(end.cycle) + ": " + exitText(end.exit_code);
  if (end.unresponsive) return "stopped answering during cycle " + std::to_string(end.cycle);
  return "served to the end; on SIGTERM " + exitText(end.exit_code);
}

std::string reloadCounts(const std::vector<ReloadRecord>& reloads) {
  int valid = 0, taken = 0, broken = 0, refused = 0;
  std::map<std::string, long> broken_kinds;
  for (const ReloadRecord& r : reloads) {
    if (isBroken(r.kind)) {
      ++broken;
      ++broken_kinds[reloadKindName(r.kind)];
      refused += r.verdict == ReloadVerdict::Refused;
    } else {
      ++valid;
      taken += r.verdict == ReloadVerdict::Accepted;
    }
  }
  return format("%zu: %d valid (%d taken: \"reloaded\"), %d with a broken calibration (%s; %d refused: \"reload failed\")",
                reloads.size(), valid, taken, broken, countsText(broken_kinds).c_str(), refused);
}

std::string reloadTimes(const std::vector<ReloadRecord>& reloads) {
  std::vector<double> ms;
  int never = 0;
  for (const ReloadRecord& r : reloads) {
    if (r.ms_to_ready >= 0.0)
      ms.push_back(r.ms_to_ready);
    else
      ++never;
  }
  if (ms.empty()) return "none";
  return format("median %.2f s, max %.2f s", quantile(ms, 0.5) / 1000.0, quantile(ms, 1.0) / 1000.0) +
         (never ? format("; %d never reported READY=1", never) : "");
}

std::string picksText(const SoakResult& r) {
  if (r.cycles_complete == 0) return "";
  return format("; %d-%d picks each, %ld in all", r.min_picks, r.max_picks, r.picks);
}

Rows summaryRows(const SoakResult& r) {
  const TallySummary& t = r.tally;
  return {
      {"cycles", format("%d/%d complete (TRIGGER, then NEXT until no_more_picks)", r.cycles_complete,
                        r.cycles_wanted) + picksText(r)},
      {"requests", format("%ld sent, %ld answered; %ld without a reply, %ld answered for another command, %ld "
                          "replies unasked; %ld connections refused",
                          t.sent, t.answered, t.lost, t.mismatched, t.extra, t.connect_failures)},
      {"replies by status", countsText(t.replies_by_status)},
      {"unexpected statuses", std::to_string(t.unexpected)},
      {"visitors", format("%d robots, %ld visits (connect, STATUS, PING, a FAILED in four, leave)", r.visitors,
                          r.visits)},
      {"reloads", reloadCounts(r.reloads)},
      {"SIGHUP to READY=1", reloadTimes(r.reloads)},
      {"binpickd", daemonText(r.daemon)},
      {"resident memory", "start " + megabytes(r.rss.start) + ", after " + std::to_string(r.warmup) +
                              " warm-up cycles " + megabytes(r.rss.warm) + ", end " + megabytes(r.rss.end) +
                              ", max " + megabytes(r.rss.max)},
      {"cycle (TRIGGER to the last NEXT)", seconds(r.cycle_ms)},
      {"cycles a reload raced", seconds(r.cycle_ms_after_reload)},
  };
}

std::vector<std::string> failures(const SoakResult& r) {
  std::vector<std::string> found;
  if (r.daemon.died) found.push_back("binpickd " + daemonText(r.daemon));
  if (r.daemon.unresponsive) found.push_back("binpickd " + daemonText(r.daemon));
  if (!r.tally.everyRequestAnsweredOnce()) found.push_back("a request was not answered exactly once");
  if (r.tally.unexpected > 0) found.push_back(std::to_string(r.tally.unexpected) + " unexpected statuses");
  if (r.tally.connect_failures > 0) found.push_back("connections refused");
  if (r.cycles_complete < r.cycles_wanted) found.push_back("cycles left incomplete");
  const long wrong_reloads =
      std::count_if(r.reloads.begin(), r.reloads.end(), [](const ReloadRecord& rec) { return !rec.asExpected(); });
  if (wrong_reloads > 0) found.push_back(std::to_string(wrong_reloads) + " reloads not taken or refused as they should");
  return found;
}

std::string verdictText(const SoakResult& r) {
  const std::vector<std::string> found = failures(r);
  if (found.empty()) return "passed";
  std::string text = "FAILED:";
  for (const std::string& f : found) text += " " + f + ";";
  text.pop_back();
  return text;
}

std::string escapedCell(std::string text) {
  for (std::size_t at = text.find('|'); at != std::string::npos; at = text.find('|', at + 2)) text.insert(at, "\\");
  return text;
}

std::string commandTable(const TallySummary& t) {
  std::string table = "| command | sent | replies by status |\n|---|---:|---|\n";
  for (const auto& [command, sent] : t.sent_by_command) {
    const auto replies = t.replies_by_command.find(command);
    table += "| " + command + " | " + std::to_string(sent) + " | " +
             (replies == t.replies_by_command.end() ? "none" : countsText(replies->second)) + " |\n";
  }
  return table;
}

std::string reloadProblems(const std::vector<ReloadRecord>& reloads) {
  std::string text;
  std::size_t shown = 0;
  for (const ReloadRecord& r : reloads) {
    if (r.asExpected() || shown++ >= kReloadProblemsShown) continue;
    const char* verdict = r.verdict == ReloadVerdict::Accepted  ? "taken"
                          : r.verdict == ReloadVerdict::Refused ? "refused"
                                                                : "no verdict in the log";
    text += "- after cycle " + std::to_string(r.after_cycle) + ", " + reloadKindName(r.kind) + ": " + verdict +
            (r.log_line.empty() ? "" : ": `" + r.log_line + "`") + "\n";
  }
  return text;
}

std::string logTable(const std::vector<LogPattern>& patterns) {
  std::string table = "| lines | first of them |\n|---:|---|\n";
  for (std::size_t i = 0; i < patterns.size() && i < kLogPatternsShown; ++i) {
    table += "| " + std::to_string(patterns[i].count) + " | " + escapedCell(patterns[i].example) + " |\n";
  }
  return table;
}

std::string today() {
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof(date), "%Y-%m-%d", std::gmtime(&now));
  return date;
}

std::string cpuName() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "unknown CPU";
}

// "[warning] binpickd: cycle 12 took 812 ms" -> "[warning] binpickd: cycle N took N ms"
std::string withoutNumbers(const std::string& line) {
  std::string pattern;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (!std::isdigit(static_cast<unsigned char>(line[i]))) {
      pattern += line[i];
    } else if (i == 0 || !std::isdigit(static_cast<unsigned char>(line[i - 1]))) {
      pattern += 'N';
    }
  }
  return pattern;
}

std::string replacedEverywhere(std::string text, const std::string& from, const std::string& to) {
  if (from.empty()) return text;
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

std::string plural(int count, const char* noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

}  // namespace

void nameDirectories(SoakResult& result, const std::vector<std::pair<std::string, std::string>>& directories) {
  for (const auto& [from, name] : directories) {
    for (LogPattern& pattern : result.log_patterns) pattern.example = replacedEverywhere(pattern.example, from, name);
    for (ReloadRecord& reload : result.reloads) reload.log_line = replacedEverywhere(reload.log_line, from, name);
    result.daemon.last_log_lines = replacedEverywhere(result.daemon.last_log_lines, from, name);
  }
}

void MemoryTrack::sample(long kilobytes) {
  if (kilobytes < 0) return;
  end = kilobytes;
  max = std::max(max, kilobytes);
}

std::vector<LogPattern> warningsAndErrors(const std::string& log_path) {
  std::map<std::string, LogPattern> by_pattern;
  std::ifstream log(log_path);
  for (std::string line; std::getline(log, line);) {
    if (line.rfind("[warning]", 0) != 0 && line.rfind("[error]", 0) != 0 && line.rfind("[critical]", 0) != 0) continue;
    LogPattern& pattern = by_pattern[withoutNumbers(line)];
    if (pattern.count++ == 0) pattern.example = line;
  }
  std::vector<LogPattern> patterns;
  for (auto& entry : by_pattern) patterns.push_back(std::move(entry.second));
  std::stable_sort(patterns.begin(), patterns.end(), [](const auto& a, const auto& b) { return a.count > b.count; });
  return patterns;
}

bool SoakResult::passed() const { return failures(*this).empty(); }

std::string consoleReport(const SoakResult& result) {
  std::string text;
  for (const auto& [key, value] : summaryRows(result)) text += "  " + key + ": " + value + "\n";
  for (const std::string& problem : result.tally.problems) text += "  problem: " + problem + "\n";
  text += reloadProblems(result.reloads);
  for (std::size_t i = 0; i < result.log_patterns.size() && i < kLogPatternsShown; ++i) {
    text += format("  log, %ld x: ", result.log_patterns[i].count) + result.log_patterns[i].example + "\n";
  }
  if (!result.daemon.last_log_lines.empty()) text += "  the daemon's last log lines:\n" + result.daemon.last_log_lines;
  return text + "soak " + verdictText(result) + "\n";
}

std::string markdownReport(const SoakResult& r) {
  std::string md = "# binpickd soak\n\n";
  md += "`" + r.command + "`, " + today() + ", " + std::to_string(std::thread::hardware_concurrency()) +
        " threads, " + cpuName() + format("; %.0f minutes.", r.minutes) + "\n\n";
  md += "binpickd on the virtual cell's test bin (12 l_brackets, replayed), every stage on " +
        plural(r.threads, "thread") + "; one robot runs the cycles and triggers again right after its last NEXT, " +
        plural(r.visitors, "other robot") + " come and go" +
        (r.reload_every > 0 ? ", and every " + plural(r.reload_every, "cycle") +
                                  " a SIGHUP lands in that window, with valid settings and with a broken "
                                  "calibration in turn"
                            : "") +
        ". WORK is the soak's working directory, SCENE the test bin's.\n\n";
  md += "**" + verdictText(r) + "**\n\n| | |\n|---|---|\n";
  for (const auto& [key, value] : summaryRows(r)) md += "| " + key + " | " + escapedCell(value) + " |\n";
  md += "\nRequests by command:\n\n" + commandTable(r.tally);
  if (!r.tally.problems.empty()) {
    md += "\nProblems (the first " + std::to_string(r.tally.problems.size()) + "):\n\n";
    for (const std::string& problem : r.tally.problems) md += "- " + problem + "\n";
  }
  if (const std::string reloads = reloadProblems(r.reloads); !reloads.empty()) {
    md += "\nReloads not taken or refused as they should have been:\n\n" + reloads;
  }
  if (!r.log_patterns.empty()) md += "\nWarnings and errors in binpickd's log (numbers as N when counting):\n\n" + logTable(r.log_patterns);
  if (!r.daemon.last_log_lines.empty()) md += "\nbinpickd's last log lines:\n\n```\n" + r.daemon.last_log_lines + "```\n";
  return md;
}

}  // namespace binpick::bench::soak
