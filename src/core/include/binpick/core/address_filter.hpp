#pragma once
// An allow-list of IPv4 clients, addresses and CIDR blocks, for the servers of the cell (the robot
// server, the web view): settings like `allowed_clients: [10.0.0.5, 192.168.1.0/24]`. Immutable
// once built: thread-safe.
#include <netinet/in.h>

#include <cstdint>
#include <string>
#include <vector>

namespace binpick::core {

class AddressFilter {
 public:
  // Entries like "10.0.0.5" or "10.0.0.0/8"; throws core::Error naming `field` and the first
  // malformed entry. An empty list allows every address.
  AddressFilter(const std::vector<std::string>& entries, const std::string& field);
  bool allows(const in_addr& address) const;
  // A dotted quad as a peer is reported ("10.0.0.5"); anything else (an IPv6 address, a name) is
  // allowed only by an empty list.
  bool allows(const std::string& address) const;
  bool allowsEveryone() const { return blocks_.empty(); }

 private:
  struct Block {
    uint32_t network;  // host byte order, host bits cleared
    uint32_t mask;
  };
  std::vector<Block> blocks_;
};

// "a.b.c.d" of `address`, for the log and error messages.
std::string addressText(const in_addr& address);

}  // namespace binpick::core
