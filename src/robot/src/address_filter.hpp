#pragma once
// Internal: the allow-list of robot controllers, IPv4 addresses and CIDR blocks. Immutable once
// built: thread-safe.
#include <netinet/in.h>

#include <cstdint>
#include <string>
#include <vector>

namespace binpick::robot::detail {

class AddressFilter {
 public:
  // Entries like "10.0.0.5" or "10.0.0.0/8"; throws core::Error naming `field` and the first
  // malformed entry. An empty list allows every address.
  AddressFilter(const std::vector<std::string>& entries, const std::string& field);
  bool allows(const in_addr& address) const;

 private:
  struct Block {
    uint32_t network;  // host byte order, host bits cleared
    uint32_t mask;
  };
  std::vector<Block> blocks_;
};

// "a.b.c.d" of `address`, for the log and error messages.
std::string addressText(const in_addr& address);

}  // namespace binpick::robot::detail
