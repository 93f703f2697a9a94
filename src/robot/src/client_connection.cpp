#include "client_connection.hpp"

#include <sys/socket.h>

#include <cerrno>
#include <utility>

#include "binpick/core/component_logger.hpp"
#include "binpick/core/error.hpp"

namespace binpick::robot::detail {
namespace {

// One recv per poll wake-up: a client that floods gets no more turns than one that does not.
constexpr std::size_t kReceiveChunk = 4096;

// The reply to a message that was no request: the command echoed when it could be read.
robot::Reply errorReply(const robot::Decoded& decoded) {
  robot::Reply reply;
  reply.command = decoded.command;
  reply.status = decoded.error;
  return reply;
}

bool isTransient(int error_number) {
  return error_number == EAGAIN || error_number == EWOULDBLOCK || error_number == EINTR;
}

}  // namespace

ClientConnection::ClientConnection(ClientId id, UniqueFd socket, std::string peer, const robot::CodecParams& codec,
                                   const ClientLimits& limits)
    : id_(id),
      socket_(std::move(socket)),
      peer_(std::move(peer)),
      codec_(codec),
      limits_(limits),
      decoder_(codec),
      idle_since_(Clock::now()),
      bad_requests_(id, peer_, limits.bad_request_log_interval) {}

void ClientConnection::markClosing(const std::string& reason) {
  if (close_reason_.empty()) close_reason_ = reason;
}

void ClientConnection::receive() {
  char chunk[kReceiveChunk];
  const ssize_t got = ::recv(socket_.get(), chunk, sizeof chunk, MSG_DONTWAIT);
  if (got == 0) return markClosing("closed by the client");
  if (got < 0) {
    if (!isTransient(errno)) markClosing("receive failed: " + errnoText(errno));
    return;
  }
  idle_since_ = Clock::now();
  decoder_.feed(chunk, static_cast<std::size_t>(got));
  if (decoder_.buffered() > limits_.max_buffered_input) {
    markClosing("more than " + std::to_string(limits_.max_buffered_input) + " bytes of an incomplete request");
  }
}

void ClientConnection::switchCodec(const robot::CodecParams& codec) {
  while (std::optional<robot::Decoded> decoded = decoder_.next()) backlog_.push_back(std::move(*decoded));
  if (decoder_.buffered() > 0) {
    core::componentLogger("robot")->warn(
        "client {} ({}): {} bytes of a request begun before the codec changed are dropped", id_, peer_,
        decoder_.buffered());
  }
  codec_ = codec;
  decoder_ = robot::RequestDecoder(codec);
}

std::optional<robot::Decoded> ClientConnection::nextMessage() {
  if (!backlog_.empty()) {
    robot::Decoded front = std::move(backlog_.front());
    backlog_.pop_front();
    return front;
  }
  return decoder_.next();
}

std::optional<robot::Request> ClientConnection::takeNextRequest() {
  if (closing() || outstanding_) return std::nullopt;
  while (std::optional<robot::Decoded> message = nextMessage()) {
    if (message->request) {
      outstanding_ = message->request->command;
      return std::move(message->request);
    }
    bad_requests_.record(*message, Clock::now());
    queueOutput(encodeOrInternalError(errorReply(*message)));
  }
  return std::nullopt;
}

bool ClientConnection::answer(const robot::Reply& reply) {
  if (!outstanding_) return false;
  if (reply.command != *outstanding_) {
    // A handler bug; the robot still gets the reply so that it is not left waiting.
    core::componentLogger("robot")->warn("client {}: reply for {} answers a {} request", id_,
                                         robot::commandKeyword(reply.command), robot::commandKeyword(*outstanding_));
  }
  outstanding_.reset();
  idle_since_ = Clock::now();  // a robot that waited long for a cycle is not idle for it
  queueOutput(encodeOrInternalError(reply));
  return true;
}

std::string ClientConnection::encodeOrInternalError(const robot::Reply& reply) {
  try {
    return robot::encodeReply(reply, codec_);
  } catch (const core::Error& error) {
    // A reply the codec cannot encode (too many integers, ...) must still answer the request.
    core::componentLogger("robot")->error("client {}: cannot encode the {} reply: {}", id_,
                                          robot::commandKeyword(reply.command), error.what());
    robot::Reply fallback;
    fallback.command = reply.command;
    fallback.status = robot::Status::InternalError;
    return robot::encodeReply(fallback, codec_);
  }
}

void ClientConnection::checkBacklog() {
  while (std::optional<robot::Decoded> message = decoder_.next()) {
    backlog_.push_back(std::move(*message));
  }
  const std::size_t waiting = backlog_.size() + (outstanding_ ? 1 : 0);
  if (waiting > limits_.max_queued_requests) {
    markClosing(std::to_string(waiting) + " requests waiting for replies (at most " +
                std::to_string(limits_.max_queued_requests) + ")");
  }
}

std::optional<ClientConnection::Clock::time_point> ClientConnection::nextDeadline() const {
  std::optional<Clock::time_point> deadline = bad_requests_.summaryDue();
  if (limits_.idle_timeout.count() > 0 && !hasRequestOutstanding() && !closing()) {
    const Clock::time_point idle_end = idle_since_ + limits_.idle_timeout;
    if (!deadline || idle_end < *deadline) deadline = idle_end;
  }
  return deadline;
}

void ClientConnection::checkTimers(Clock::time_point now) {
  bad_requests_.flushIfDue(now);
  if (limits_.idle_timeout.count() > 0 && !hasRequestOutstanding() && now >= idle_since_ + limits_.idle_timeout) {
    markClosing("idle for " + std::to_string(limits_.idle_timeout.count()) + " ms (idle_timeout_ms)");
  }
}

void ClientConnection::queueOutput(const std::string& bytes) {
  output_ += bytes;
  flush();
}

void ClientConnection::flush() {
  while (!closing() && sent_ < output_.size()) {
    const ssize_t sent =
        ::send(socket_.get(), output_.data() + sent_, output_.size() - sent_, MSG_NOSIGNAL | MSG_DONTWAIT);
    if (sent < 0) {
      if (errno == EINTR) continue;
      if (errno == EAGAIN || errno == EWOULDBLOCK) break;
      return markClosing("send failed: " + errnoText(errno));
    }
    sent_ += static_cast<std::size_t>(sent);
  }
  // Drop the sent prefix once it is most of the buffer: cheap, and the buffer stays small.
  if (sent_ > 0 && sent_ * 2 >= output_.size()) {
    output_.erase(0, sent_);
    sent_ = 0;
  }
  const std::size_t unsent = output_.size() - sent_;
  if (unsent > limits_.max_buffered_output) {
    markClosing("slow client: " + std::to_string(unsent) + " bytes of replies unread (at most " +
                std::to_string(limits_.max_buffered_output) + ")");
  }
}

}  // namespace binpick::robot::detail
