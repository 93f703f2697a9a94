#include "binpick/core/address_filter.hpp"

#include <arpa/inet.h>

#include <cctype>
#include <optional>

#include "binpick/core/error.hpp"

namespace binpick::core {
namespace {

// The prefix length of "/N": digits only, so that "/+8" or "/ 8" are refused, not read as 8.
std::optional<int> parsePrefixLength(const std::string& text) {
  if (text.empty() || text.size() > 2) return std::nullopt;
  int value = 0;
  for (char c : text) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return std::nullopt;
    value = value * 10 + (c - '0');
  }
  if (value > 32) return std::nullopt;
  return value;
}

uint32_t maskOfPrefix(int prefix_length) {
  // A shift by 32 is undefined behaviour: /0 gets its mask spelled out.
  return prefix_length == 0 ? 0u : ~uint32_t{0} << (32 - prefix_length);
}

}  // namespace

AddressFilter::AddressFilter(const std::vector<std::string>& entries, const std::string& field) {
  for (const std::string& entry : entries) {
    const std::size_t slash = entry.find('/');
    const std::string address_part = entry.substr(0, slash);
    in_addr address{};
    // inet_pton accepts dotted quads only (no "10.1", no hex), which is what a config should say.
    const bool address_ok = inet_pton(AF_INET, address_part.c_str(), &address) == 1;
    std::optional<int> prefix = 32;
    if (slash != std::string::npos) prefix = parsePrefixLength(entry.substr(slash + 1));
    if (!address_ok || !prefix) {
      throw Error(field + " entry \"" + entry +
                  "\" is not an IPv4 address or CIDR block (like 10.0.0.5 or 10.0.0.0/8)");
    }
    const uint32_t mask = maskOfPrefix(*prefix);
    blocks_.push_back({ntohl(address.s_addr) & mask, mask});
  }
}

bool AddressFilter::allows(const in_addr& address) const {
  if (blocks_.empty()) return true;
  const uint32_t host_order = ntohl(address.s_addr);
  for (const Block& block : blocks_) {
    if ((host_order & block.mask) == block.network) return true;
  }
  return false;
}

bool AddressFilter::allows(const std::string& address) const {
  if (blocks_.empty()) return true;
  in_addr parsed{};
  return inet_pton(AF_INET, address.c_str(), &parsed) == 1 && allows(parsed);
}

std::string addressText(const in_addr& address) {
  char text[INET_ADDRSTRLEN] = {};
  inet_ntop(AF_INET, &address, text, sizeof text);
  return text;
}

}  // namespace binpick::core
