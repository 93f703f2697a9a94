#include <arpa/inet.h>

#include "address_filter.hpp"
#include "binpick/cell/robot_server.hpp"
#include "binpick/io/error.hpp"

namespace binpick::cell {

void RobotServerParams::validate() const {
  const std::string owner = "robot_server";
  in_addr address{};
  requireField(inet_pton(AF_INET, bind_address.c_str(), &address) == 1, owner, "bind_address",
               "an IPv4 address", bind_address);
  requireField(port >= 0 && port <= 65535, owner, "port", "in [0, 65535]", port);
  // Parsing is the check; the filter itself is built again by the server.
  detail::AddressFilter{allowed_clients, owner + ".allowed_clients"};
  requireField(max_clients >= 1, owner, "max_clients", ">= 1", max_clients);
  requireField(max_queued_requests >= 1, owner, "max_queued_requests", ">= 1",
               max_queued_requests);
  // A request the codec accepts must fit, or every long request would cost the connection.
  requireField(max_buffered_input >= codec.max_line_length &&
                   max_buffered_input >= robot::kMaxBinaryRequestSize,
               owner, "max_buffered_input", ">= codec.max_line_length and the longest binary request",
               max_buffered_input);
  // One reply must fit, or the first reply to a client that is slow to read would cost it.
  requireField(max_buffered_output >= robot::kBinaryReplySize &&
                   max_buffered_output >= codec.max_line_length,
               owner, "max_buffered_output", ">= codec.max_line_length and the binary reply size",
               max_buffered_output);
  codec.validate();
}

}  // namespace binpick::cell
