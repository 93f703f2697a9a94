#include <arpa/inet.h>
#include <exception>
#include <tuple>

#include "binpick/core/address_filter.hpp"
#include "binpick/core/component_logger.hpp"
#include "binpick/core/error.hpp"
#include "binpick/robot/robot_server.hpp"
#include "server_impl.hpp"

namespace binpick::robot {
namespace {

const std::string kOwner = "robot_server";

detail::ClientLimits limitsOf(const RobotServerParams& params) {
  detail::ClientLimits limits;
  limits.max_queued_requests = params.max_queued_requests;
  limits.max_buffered_input = params.max_buffered_input;
  limits.max_buffered_output = params.max_buffered_output;
  limits.idle_timeout = std::chrono::milliseconds(params.idle_timeout_ms);
  limits.bad_request_log_interval = std::chrono::milliseconds(params.bad_request_log_interval_ms);
  return limits;
}

bool sameCodec(const robot::CodecParams& a, const robot::CodecParams& b) {
  return std::tie(a.framing, a.orientation, a.max_line_length, a.position_decimals, a.orientation_decimals,
                  a.byte_order, a.position_scale, a.orientation_scale) ==
         std::tie(b.framing, b.orientation, b.max_line_length, b.position_decimals, b.orientation_decimals,
                  b.byte_order, b.position_scale, b.orientation_scale);
}

}  // namespace

RobotServer::Impl::Impl(const RobotServerParams& params, RequestHandler& request_handler)
    : limits(limitsOf(params)),
      max_clients(params.max_clients),
      keepalive{params.keepalive_idle_s, params.keepalive_interval_s, params.keepalive_count},
      handler(request_handler),
      listener(detail::listenTcp(params.bind_address, params.port)),
      wake_fd(detail::makeEventFd()),
      port(detail::boundPort(listener.get())),
      codec(params.codec),
      allowed(std::make_shared<const core::AddressFilter>(params.allowed_clients, kOwner + ".allowed_clients")) {}

RobotServer::RobotServer(const RobotServerParams& params, RequestHandler& handler) {
  params.validate();
  impl_ = std::make_unique<Impl>(params, handler);
  core::componentLogger("robot")->info("listening on {}:{}", params.bind_address, impl_->port);
}

RobotServer::~RobotServer() = default;

int RobotServer::port() const { return impl_->port; }

void RobotServer::run() {
  if (impl_->running.exchange(true)) throw core::Error("robot server: run() is already running");
  if (!impl_->listener.valid() && !impl_->stop_requested.load()) {
    impl_->running.store(false);
    throw core::Error("robot server: the listening socket was closed by a failure; create a new server");
  }
  // Whichever way the loop ends, the clients hear of it and a later run() finds a clean state.
  struct Finish {
    Impl& impl;
    const char* reason;
    ~Finish() {
      impl.deliverRepliesBeforeClosing();
      impl.closeAll(reason);
      impl.listener.reset();
      impl.running.store(false);
    }
  } finish{*impl_, "the server stopped"};
  try {
    impl_->serve();
  } catch (const std::exception&) {
    finish.reason = "the server failed";
    throw;
  }
}

void RobotServer::stop() {
  impl_->stop_requested.store(true);
  impl_->wake();
}

void RobotServer::reply(ClientId client, const robot::Reply& reply) {
  // Replies given up to the end of run() still go out (deliverRepliesBeforeClosing): a service
  // answers its waiting robots, then stops the server. After run() nothing takes them any more.
  if (!impl_->running.load()) return;
  {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    impl_->incoming_replies.emplace_back(client, reply);
  }
  impl_->wake();
}

std::size_t RobotServer::clientCount() const { return impl_->client_count.load(); }

std::vector<ConnectedClient> RobotServer::clients() const {
  std::vector<ConnectedClient> list;
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  for (const auto& entry : impl_->connected) list.push_back(entry.second);  // ids grow: connection order
  return list;
}

std::size_t RobotServer::setCodec(const robot::CodecParams& codec) {
  codec.validate();
  core::requireField(codec.max_line_length <= impl_->limits.max_buffered_input &&
                         codec.max_line_length <= impl_->limits.max_buffered_output,
                     kOwner + ".codec", "max_line_length", "<= max_buffered_input and max_buffered_output",
                     codec.max_line_length);
  {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    if (sameCodec(impl_->codec, codec)) return impl_->connected.size();
    impl_->codec = codec;
    ++impl_->codec_changes;
  }
  impl_->wake();
  return clientCount();
}

void RobotServer::setAllowedClients(const std::vector<std::string>& allowed) {
  auto filter = std::make_shared<const core::AddressFilter>(allowed, kOwner + ".allowed_clients");
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->allowed = std::move(filter);
}

void RobotServerParams::validate(const std::string& owner) const {
  in_addr address{};
  core::requireField(inet_pton(AF_INET, bind_address.c_str(), &address) == 1, owner, "bind_address", "an IPv4 address",
                     bind_address);
  core::requireField(port >= 0 && port <= 65535, owner, "port", "in [0, 65535]", port);
  // Parsing is the check; the filter itself is built again by the server.
  core::AddressFilter{allowed_clients, owner + ".allowed_clients"};
  core::requireField(max_clients >= 1, owner, "max_clients", ">= 1", max_clients);
  core::requireField(idle_timeout_ms >= 0, owner, "idle_timeout_ms", ">= 0 (0: no idle timeout)", idle_timeout_ms);
  // Linux's limits for TCP_KEEPIDLE, TCP_KEEPINTVL and TCP_KEEPCNT.
  core::requireField(keepalive_idle_s >= 0 && keepalive_idle_s <= 32767, owner, "keepalive_idle_s",
                     "in [0, 32767] seconds (0: no keepalive)", keepalive_idle_s);
  core::requireField(keepalive_interval_s >= 1 && keepalive_interval_s <= 32767, owner, "keepalive_interval_s",
                     "in [1, 32767] seconds", keepalive_interval_s);
  core::requireField(keepalive_count >= 1 && keepalive_count <= 127, owner, "keepalive_count", "in [1, 127]",
                     keepalive_count);
  core::requireField(bad_request_log_interval_ms >= 1, owner, "bad_request_log_interval_ms", ">= 1",
                     bad_request_log_interval_ms);
  core::requireField(max_queued_requests >= 1, owner, "max_queued_requests", ">= 1", max_queued_requests);
  // The codec first: a bad max_line_length is named as itself, not as a buffer that cannot hold it.
  codec.validate(owner);
  // A request the codec accepts must fit, or every long request would cost the connection.
  core::requireField(max_buffered_input >= codec.max_line_length && max_buffered_input >= robot::kMaxBinaryRequestSize,
                     owner, "max_buffered_input", ">= max_line_length and the longest binary request",
                     max_buffered_input);
  // One reply must fit, or the first reply to a client that is slow to read would cost it.
  core::requireField(max_buffered_output >= robot::kBinaryReplySize && max_buffered_output >= codec.max_line_length,
                     owner, "max_buffered_output", ">= max_line_length and the binary reply size", max_buffered_output);
}

}  // namespace binpick::robot
