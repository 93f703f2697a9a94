#pragma once
// Internal: the datagram side of the notify protocol.
// Stateless functions: thread-safe.
#include <string>

namespace binpick::cell::systemd_detail {

// Throws core::Error naming NOTIFY_SOCKET unless `address` is "/absolute/path" or "@name"
// and fits into a socket address.
void checkNotifyAddress(const std::string& address);

// Sends `payload` as one datagram to `address` (checked), waiting at most a second for room in a
// full queue. Returns "" when sent, otherwise why it was not.
std::string sendDatagram(const std::string& address, const std::string& payload) noexcept;

}  // namespace binpick::cell::systemd_detail
