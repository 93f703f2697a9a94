#include "soak_reloads.hpp"

#include <signal.h>

#include <filesystem>
#include <fstream>

namespace binpick::bench::soak {
namespace {

using namespace std::chrono_literals;

constexpr ReloadKind kBrokenKinds[] = {ReloadKind::Garbage, ReloadKind::Truncated, ReloadKind::Removed};

// binpickd's own words (src/daemon/daemon.cpp): "reloaded FILE" or "reload failed, keeping ...".
constexpr const char* kRefusedText = "reload failed";
constexpr const char* kAcceptedText = "reloaded ";

std::string textFrom(const std::string& path, std::uintmax_t offset) {
  std::ifstream file(path, std::ios::binary);
  file.seekg(static_cast<std::streamoff>(offset));
  return std::string(std::istreambuf_iterator<char>(file), {});
}

std::string lineAround(const std::string& text, std::size_t at) {
  const std::size_t begin = text.rfind('\n', at);
  const std::size_t end = text.find('\n', at);
  const std::size_t from = begin == std::string::npos ? 0 : begin + 1;
  return text.substr(from, end == std::string::npos ? std::string::npos : end - from);
}

}  // namespace

ReloadKind Reloads::nextKind() const {
  const std::size_t n = records_.size();
  if (n % 2 == 1) return ReloadKind::Valid;
  return kBrokenKinds[(n / 2) % std::size(kBrokenKinds)];
}

void Reloads::fire(ReloadKind kind, int after_cycle) {
  // The files of a reload must stay as they are until binpickd has read them.
  settle(120s);
  if (cell_.daemon().wait(0ms)) return;  // gone: nothing to reload, and its pid may be another's by now
  cell_.prepareReload(kind);
  std::error_code no_log;
  log_offset_ = std::filesystem::file_size(cell_.logPath(), no_log);
  if (no_log) log_offset_ = 0;
  ReloadRecord record;
  record.kind = kind;
  record.after_cycle = after_cycle;
  records_.push_back(record);
  signalled_ = NotifyListener::Clock::now();
  cell_.daemon().signal(SIGHUP);
  pending_ = true;
}

bool Reloads::settle(std::chrono::milliseconds timeout) {
  if (!pending_) return true;
  ReloadRecord& record = records_.back();
  // In slices: a daemon that died mid-reload is noticed within a second, not after the timeout.
  while (NotifyListener::Clock::now() - signalled_ < timeout) {
    if (const auto ready = cell_.notifications().readyAfter(signalled_, 1s)) {
      record.ms_to_ready = std::chrono::duration<double, std::milli>(*ready - signalled_).count();
      break;
    }
    if (cell_.daemon().wait(0ms)) break;
  }
  pending_ = false;
  readVerdict(record);
  return record.ms_to_ready >= 0.0;
}

// The daemon writes its verdict before it reports READY=1, so the line is in the log by now.
void Reloads::readVerdict(ReloadRecord& record) const {
  const std::string text = textFrom(cell_.logPath(), log_offset_);
  if (const std::size_t at = text.find(kRefusedText); at != std::string::npos) {
    record.verdict = ReloadVerdict::Refused;
    record.log_line = lineAround(text, at);
  } else if (const std::size_t accepted = text.find(kAcceptedText); accepted != std::string::npos) {
    record.verdict = ReloadVerdict::Accepted;
    record.log_line = lineAround(text, accepted);
  }
}

}  // namespace binpick::bench::soak
