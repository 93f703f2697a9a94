#pragma once
// Internal: one robot controller's connection: its socket, decoder, the messages received but not
// yet answered (in order), the request with the handler, and the replies not yet sent. It never
// throws for what the client does: it marks itself closing with a reason and the server closes
// it. Used by the server thread only: not thread-safe.
#include <chrono>
#include <cstddef>
#include <deque>
#include <optional>
#include <string>

#include "bad_request_log.hpp"
#include "binpick/robot/protocol.hpp"
#include "binpick/robot/robot_server.hpp"
#include "socket_util.hpp"

namespace binpick::robot::detail {

struct ClientLimits {
  std::size_t max_queued_requests = 16;
  std::size_t max_buffered_input = 4096;
  std::size_t max_buffered_output = 65536;
  std::chrono::milliseconds idle_timeout{0};  // 0: none
  std::chrono::milliseconds bad_request_log_interval{60000};
};

class ClientConnection {
 public:
  using Clock = std::chrono::steady_clock;

  ClientConnection(ClientId id, UniqueFd socket, std::string peer, const robot::CodecParams& codec,
                   const ClientLimits& limits);

  ClientId id() const { return id_; }
  int fd() const { return socket_.get(); }
  const std::string& peer() const { return peer_; }  // "address:port"
  bool closing() const { return !close_reason_.empty(); }
  const std::string& closeReason() const { return close_reason_; }
  // Keeps the first reason: it is the cause, later ones are consequences.
  void markClosing(const std::string& reason);

  // Reads one chunk from the socket into the decoder; marks closing on end of stream, an error or
  // too much incomplete input.
  void receive();
  // The next request for the handler, unless one is already with it. Error replies for the
  // messages before it are queued for sending on the way, so they keep their place in line.
  std::optional<robot::Request> takeNextRequest();
  bool awaitingReply() const { return outstanding_.has_value(); }
  // A request with the handler or waiting to go to it: the robot is waiting for a reply.
  bool hasRequestOutstanding() const { return outstanding_.has_value() || !backlog_.empty(); }
  // Since when the client has sent nothing and, after the last reply, asked nothing.
  Clock::time_point idleSince() const { return idle_since_; }
  const std::optional<robot::Command>& outstandingCommand() const { return outstanding_; }
  // Answers the request with the handler; false (nothing sent) when none is.
  bool answer(const robot::Reply& reply);
  // The codec from the next message on (a reload): messages already decoded keep their place,
  // the bytes of one begun in the old codec are dropped (logged).
  void switchCodec(const robot::CodecParams& codec);
  // Moves what the decoder holds into the queue of unanswered messages; marks closing when more
  // than max_queued_requests wait (the client pipelines instead of waiting for its replies).
  void checkBacklog();

  // Sends buffered replies; marks closing on a send error or when more than max_buffered_output
  // bytes stay unsent (the client does not read).
  void flush();
  bool hasUnsentOutput() const { return sent_ < output_.size(); }

  // The next moment checkTimers() has something to do: the idle timeout, a log summary.
  std::optional<Clock::time_point> nextDeadline() const;
  // Marks closing once idle for idle_timeout; logs a due bad-request summary.
  void checkTimers(Clock::time_point now);
  // Logs what the bad-request log still counts (call when closing the connection).
  void flushLog() { bad_requests_.flush(Clock::now()); }

 private:
  std::optional<robot::Decoded> nextMessage();
  void queueOutput(const std::string& bytes);
  std::string encodeOrInternalError(const robot::Reply& reply);

  ClientId id_;
  UniqueFd socket_;
  std::string peer_;
  robot::CodecParams codec_;
  ClientLimits limits_;
  robot::RequestDecoder decoder_;
  std::deque<robot::Decoded> backlog_;         // received, not yet handed over or answered
  std::optional<robot::Command> outstanding_;  // the request with the handler
  std::string output_;
  std::size_t sent_ = 0;  // bytes of output_ already sent
  std::string close_reason_;
  Clock::time_point idle_since_;
  BadRequestLog bad_requests_;
};

}  // namespace binpick::robot::detail
