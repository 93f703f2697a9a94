#pragma once
// The TCP server the robot controllers connect to. One thread runs the event loop (poll): it
// accepts clients from the allow-list, reads requests with the configured framing, hands each to
// the RequestHandler and writes the replies. A client gets its replies in request order; its next
// request is handed over only once the previous one is answered (robots are synchronous), while
// every other client is served meanwhile. A client that sends garbage gets error replies (in
// order with its other replies); one that queues more than max_queued_requests unanswered
// requests, holds more than max_buffered_input bytes of an incomplete request, or does not read
// its replies (max_buffered_output), is disconnected; no client can stall another or the handler.
// Slots cannot be held forever: a client idle for idle_timeout_ms is disconnected, TCP keepalive
// notices peers that died without closing, and a newcomer finding max_clients connected takes
// the slot of the longest-idle client without a request outstanding (refused only when every
// client has one). Bad requests are logged rate-limited per client: the first
// kBadRequestsLoggedInFull one by one, then one summary line per bad_request_log_interval_ms.
//
// Thread-safety: reply(), stop(), clientCount(), clients(), setCodec() and setAllowedClients() may be called
// from any thread; run() from one thread at a time. The destructor joins nothing (run() runs on
// the caller's thread): call stop() and wait for run() to return before destroying the server.
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "binpick/robot/protocol.hpp"

namespace binpick::robot {

constexpr int kBadRequestsLoggedInFull = 5;  // per client, before only summaries are logged

struct RobotServerParams {
  std::string bind_address = "0.0.0.0";      // IPv4 address to listen on
  int port = 50100;                          // 0: any free port (tests; see port())
  std::vector<std::string> allowed_clients;  // IPv4 addresses or CIDR blocks; empty: any
  // When this many are connected, a newcomer replaces the client idle longest among those without
  // a request outstanding; it is refused only when every client has one.
  int max_clients = 8;
  // A client that has sent nothing and had no request outstanding for this long is disconnected
  // (a controller that went away without closing frees its slot). 0: never. A robot polling once
  // a cycle never comes near the default, 10 minutes.
  int idle_timeout_ms = 600000;
  // TCP keepalive on every client socket: after keepalive_idle_s without traffic a probe every
  // keepalive_interval_s, and keepalive_count unanswered probes drop the connection. With the
  // defaults a peer that lost power or its cable is noticed within 30 + 3 * 10 = 60 s.
  // keepalive_idle_s 0: no keepalive.
  int keepalive_idle_s = 30;
  int keepalive_interval_s = 10;
  int keepalive_count = 3;
  // After a client's first kBadRequestsLoggedInFull bad requests, at most one summary line per
  // this interval tells how many more there were.
  int bad_request_log_interval_ms = 60000;
  // Requests received but not yet answered, per client, the one with the handler included. A
  // robot sends one at a time; a client that pipelines more is disconnected.
  std::size_t max_queued_requests = 16;
  // Bytes of an incomplete request held per client; at least codec.max_line_length.
  std::size_t max_buffered_input = 4096;
  std::size_t max_buffered_output = 65536;  // bytes of unread replies per client
  robot::CodecParams codec;
  // Throws core::Error naming owner.FIELD (codec fields included); the owner is where the
  // settings were read from (binpickd: "robot").
  void validate(const std::string& owner = "robot_server") const;
};

using ClientId = uint64_t;  // never reused within a server's life

// A connected client, as observers (the web view) list them.
struct ConnectedClient {
  ClientId id = 0;
  std::string peer;  // "address:port"
  std::chrono::system_clock::time_point since;
};

// Called on the server thread; must not block. It answers now or later by calling
// RobotServer::reply(client, ...) exactly once per request (from any thread, this one included).
// Replies for a client that has gone are dropped. A handle() that throws has not answered: the
// server answers that request with InternalError itself.
class RequestHandler {
 public:
  virtual ~RequestHandler() = default;
  virtual void handle(ClientId client, const robot::Request& request) = 0;
  // The client is gone (it closed, broke a limit, or the server stopped); its outstanding
  // request, if any, need not be answered.
  virtual void disconnected(ClientId /*client*/) {}
};

class RobotServer {
 public:
  // Validates params, then binds and listens at once: throws core::Error naming the address
  // and port when it cannot (address in use, not an IPv4 address).
  RobotServer(const RobotServerParams& params, RequestHandler& handler);
  ~RobotServer();  // closes the sockets; see the thread-safety note above
  RobotServer(const RobotServer&) = delete;
  RobotServer& operator=(const RobotServer&) = delete;

  int port() const;  // the bound port
  // Serves until stop(), then writes out the replies given so far (at most 500 ms for clients
  // that do not read), closes every client (handler.disconnected for each) and the listening
  // socket. Problems of one client never end it; a failing listening socket or poll()
  // throws core::Error. A stopped server stays stopped: run() then returns at once.
  void run();
  void stop();
  void reply(ClientId client, const robot::Reply& reply);
  std::size_t clientCount() const;
  // The clients connected now, in the order they connected.
  std::vector<ConnectedClient> clients() const;
  // Takes new codec settings (SIGHUP reload) for every client: one codec at any moment, so that
  // what the cell checks its picks against is what every robot hears. Connected clients switch
  // between two messages: requests received before are answered as decoded, the replies after
  // it are in the new codec, and the bytes of a request begun in the old codec are dropped (the
  // log says so). Bind address and port changes need a restart. Returns the number of clients
  // connected at the change; throws core::Error naming the field for invalid settings and keeps
  // the old ones.
  std::size_t setCodec(const robot::CodecParams& codec);
  // For connections opened from now on; throws core::Error naming a malformed entry.
  void setAllowedClients(const std::vector<std::string>& allowed);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace binpick::robot
