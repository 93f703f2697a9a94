#include "cycle_names.hpp"

#include <cstdio>
#include <ctime>
#include <regex>
#include <tuple>

namespace binpick::cell::artefacts_detail {

namespace {

// Anchored by regex_match; the suffix is short enough to fit a uint32_t.
const std::regex& cycleNamePattern() {
  static const std::regex pattern("cycle-([0-9]{6,})-([0-9]{8}T[0-9]{6}Z)(?:-([1-9][0-9]{0,8}))?");
  return pattern;
}

std::string utcCompact(std::chrono::system_clock::time_point when) {
  const std::time_t seconds = std::chrono::system_clock::to_time_t(when);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y%m%dT%H%M%SZ", &utc);
  return text;
}

}  // namespace

std::string cycleDirectoryName(uint64_t cycle, std::chrono::system_clock::time_point when, uint32_t suffix) {
  char number[32];
  std::snprintf(number, sizeof number, "%06llu", static_cast<unsigned long long>(cycle));
  std::string name = "cycle-" + std::string(number) + "-" + utcCompact(when);
  if (suffix > 0) name += "-" + std::to_string(suffix);
  return name;
}

std::optional<CycleName> parseCycleDirectoryName(const std::string& name) {
  std::smatch match;
  if (!std::regex_match(name, match, cycleNamePattern())) return std::nullopt;
  CycleName parsed;
  parsed.name = name;
  parsed.number = match[1].str();
  parsed.timestamp = match[2].str();
  if (match[3].matched) parsed.suffix = static_cast<uint32_t>(std::stoul(match[3].str()));
  return parsed;
}

bool isPartialCycleName(const std::string& name) {
  return name.rfind(kPartialPrefix, 0) == 0 && parseCycleDirectoryName(name.substr(kPartialPrefix.size())).has_value();
}

bool savedBefore(const CycleName& a, const CycleName& b) {
  // Fixed-width timestamps compare as text; numbers of different widths compare by width first.
  return std::make_tuple(a.timestamp, a.number.size(), a.number, a.suffix) <
         std::make_tuple(b.timestamp, b.number.size(), b.number, b.suffix);
}

}  // namespace binpick::cell::artefacts_detail
