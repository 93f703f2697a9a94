// The server thread's side of requests and replies: handing requests to the handler one at a
// time per client, applying the replies other threads queued, and closing clients.
#include <poll.h>

#include <cerrno>
#include <chrono>
#include <exception>
#include <string>
#include <vector>

#include "binpick/core/component_logger.hpp"
#include "server_impl.hpp"

namespace binpick::robot {

void RobotServer::Impl::serveReadyClients() {
  while (!ready.empty()) {
    const ClientId id = ready.front();
    ready.pop_front();
    const auto found = clients.find(id);
    if (found == clients.end()) continue;
    detail::ClientConnection& client = *found->second;
    while (std::optional<robot::Request> request = client.takeNextRequest()) {
      handOver(client, *request);
      // A handler that answered at once frees the client for its next request now, without a
      // trip through poll() per pipelined request.
      applyReplies();
    }
    client.checkBacklog();
  }
}

void RobotServer::Impl::handOver(detail::ClientConnection& client, const robot::Request& request) {
  std::string failure;
  try {
    handler.handle(client.id(), request);
    return;
  } catch (const std::exception& error) {
    failure = error.what();
  } catch (...) {
    failure = "unknown exception";
  }
  // The robot must not wait forever for a reply the handler will never send.
  core::componentLogger("robot")->error("client {}: the handler failed on {}: {}", client.id(),
                                        robot::commandKeyword(request.command), failure);
  robot::Reply reply;
  reply.command = request.command;
  reply.status = robot::Status::InternalError;
  client.answer(reply);
}

void RobotServer::Impl::applyReplies() {
  std::vector<std::pair<ClientId, robot::Reply>> replies;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    replies.swap(incoming_replies);
  }
  for (const auto& [id, reply] : replies) {
    const auto found = clients.find(id);
    if (found == clients.end() || found->second->closing()) {
      core::componentLogger("robot")->debug("reply for client {} dropped: the client has gone", id);
      continue;
    }
    if (!found->second->answer(reply)) {
      core::componentLogger("robot")->warn("reply {} for client {} dropped: no request outstanding",
                                           robot::commandKeyword(reply.command), id);
      continue;
    }
    ready.push_back(id);
  }
}

void RobotServer::Impl::closeClosingClients() {
  for (auto it = clients.begin(); it != clients.end();) {
    const auto entry = it++;
    if (entry->second->closing()) closeClient(entry);
  }
}

void RobotServer::Impl::closeClient(std::map<ClientId, std::unique_ptr<detail::ClientConnection>>::iterator entry) {
  std::unique_ptr<detail::ClientConnection> client = std::move(entry->second);
  clients.erase(entry);
  client_count.store(clients.size());
  {
    const std::lock_guard<std::mutex> lock(mutex);
    connected.erase(client->id());
  }
  disconnect(std::move(client));
}

void RobotServer::Impl::checkClientTimers() {
  const auto now = std::chrono::steady_clock::now();
  for (auto& entry : clients) entry.second->checkTimers(now);
}

void RobotServer::Impl::deliverRepliesBeforeClosing() {
  constexpr auto kStopFlushTime = std::chrono::milliseconds(500);
  applyReplies();
  const auto deadline = std::chrono::steady_clock::now() + kStopFlushTime;
  for (;;) {
    std::vector<pollfd> waiting;
    std::vector<detail::ClientConnection*> owners;
    for (auto& entry : clients) {
      if (entry.second->closing() || !entry.second->hasUnsentOutput()) continue;
      waiting.push_back(pollfd{entry.second->fd(), POLLOUT, 0});
      owners.push_back(entry.second.get());
    }
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (waiting.empty() || left.count() <= 0) return;
    if (::poll(waiting.data(), waiting.size(), static_cast<int>(left.count())) < 0 && errno != EINTR) return;
    for (std::size_t i = 0; i < waiting.size(); ++i) {
      if (waiting[i].revents != 0) owners[i]->flush();
    }
  }
}

void RobotServer::Impl::closeAll(const char* reason) {
  for (auto& entry : clients) entry.second->markClosing(reason);
  closeClosingClients();
}

void RobotServer::Impl::disconnect(std::unique_ptr<detail::ClientConnection> client) {
  const ClientId id = client->id();
  client->flushLog();
  core::componentLogger("robot")->info("client {} ({}) disconnected: {}", id, client->peer(), client->closeReason());
  client.reset();  // the socket closes before the handler hears of it
  try {
    handler.disconnected(id);
  } catch (const std::exception& error) {
    core::componentLogger("robot")->error("client {}: the handler failed on disconnect: {}", id, error.what());
  } catch (...) {
    core::componentLogger("robot")->error("client {}: the handler failed on disconnect", id);
  }
}

}  // namespace binpick::robot
