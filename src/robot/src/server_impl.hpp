#pragma once
// Internal: the state of a RobotServer. Fields above the mutex are set in the constructor (the
// listener is closed when run() ends); those it guards are shared with the threads calling
// reply(), clients(), setCodec() and setAllowedClients(); the atomics with any thread; the rest belong to
// the thread in run().
#include <poll.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "binpick/core/address_filter.hpp"
#include "binpick/robot/robot_server.hpp"
#include "client_connection.hpp"
#include "socket_util.hpp"

namespace binpick::robot {

struct RobotServer::Impl {
  Impl(const RobotServerParams& params, RequestHandler& request_handler);

  void serve();  // the loop of run()
  void wake() { detail::signalEventFd(wake_fd.get()); }

  // Server thread only.
  std::vector<pollfd> pollSet(std::vector<ClientId>& client_of_entry) const;
  int pollTimeoutMs() const;
  void acceptClients();
  void admit(detail::UniqueFd socket, const sockaddr_in& peer);
  // max_clients are connected: closes the longest-idle client without a request outstanding;
  // false (nothing closed) when every client has one.
  bool makeRoomFor(const std::string& newcomer);
  void checkClientTimers();
  void serveReadyClients();
  void handOver(detail::ClientConnection& client, const robot::Request& request);
  void applyReplies();
  void closeClosingClients();
  void closeClient(std::map<ClientId, std::unique_ptr<detail::ClientConnection>>::iterator entry);
  void closeAll(const char* reason);
  // A setCodec() since the last call: every connected client switches now.
  void applyCodecChange();
  // Applies the replies given so far and writes out what clients have not been sent, waiting for
  // slow sockets at most kStopFlushTime in all: a robot hears its internal_error before the close.
  void deliverRepliesBeforeClosing();
  void disconnect(std::unique_ptr<detail::ClientConnection> client);

  detail::ClientLimits limits;
  int max_clients;
  // TCP keepalive of client sockets; idle_s 0: off.
  struct KeepAlive {
    int idle_s, interval_s, count;
  } keepalive;
  RequestHandler& handler;
  detail::UniqueFd listener;
  detail::UniqueFd wake_fd;
  int port = 0;

  std::mutex mutex;
  std::vector<std::pair<ClientId, robot::Reply>> incoming_replies;
  robot::CodecParams codec;
  uint64_t codec_changes = 0;  // setCodec() calls that changed it; the server thread applies them
  std::shared_ptr<const core::AddressFilter> allowed;
  std::map<ClientId, ConnectedClient> connected;  // what clients() lists, kept beside `clients`

  std::atomic<bool> stop_requested{false};
  std::atomic<bool> running{false};
  std::atomic<std::size_t> client_count{0};

  std::map<ClientId, std::unique_ptr<detail::ClientConnection>> clients;
  std::deque<ClientId> ready;  // clients whose next request may be handed over
  ClientId next_id = 1;
  uint64_t codec_changes_applied = 0;
  // Out of descriptors: accepting pauses, or the listener would wake poll() in a busy loop.
  std::chrono::steady_clock::time_point accept_paused_until{};
};

}  // namespace binpick::robot
