// The event loop of RobotServer::run(): poll() over the wake-up eventfd, the listening socket
// and the clients, then accepting, reading, handing requests over and applying replies.
#include <arpa/inet.h>

#include <algorithm>
#include <cerrno>
#include <exception>
#include <limits>
#include <optional>
#include <string>

#include "binpick/core/component_logger.hpp"
#include "binpick/core/error.hpp"
#include "server_impl.hpp"

namespace binpick::robot {
namespace {

constexpr std::size_t kWakeEntry = 0;
constexpr std::size_t kListenerEntry = 1;
constexpr std::size_t kFirstClientEntry = 2;
// At most this many connections are accepted per wake-up: a connect flood cannot starve the
// connected robots.
constexpr int kAcceptBatch = 16;
constexpr auto kAcceptPause = std::chrono::milliseconds(100);

bool isFatalAcceptError(int error_number) {
  return error_number == EBADF || error_number == EINVAL || error_number == ENOTSOCK || error_number == EFAULT;
}

bool isOutOfResources(int error_number) {
  return error_number == EMFILE || error_number == ENFILE || error_number == ENOBUFS || error_number == ENOMEM;
}

}  // namespace

void RobotServer::Impl::serve() {
  while (!stop_requested.load()) {
    std::vector<ClientId> client_of_entry;
    std::vector<pollfd> entries = pollSet(client_of_entry);
    if (::poll(entries.data(), entries.size(), pollTimeoutMs()) < 0) {
      if (errno == EINTR) continue;
      throw core::Error("robot server: poll failed: " + detail::errnoText(errno));
    }
    if (entries[kWakeEntry].revents != 0) detail::drainEventFd(wake_fd.get());
    applyCodecChange();  // before this round's bytes are decoded
    const short listener_events = entries[kListenerEntry].revents;
    if (listener_events & POLLNVAL) throw core::Error("robot server: the listening socket is gone");
    if (listener_events & (POLLIN | POLLERR)) acceptClients();
    for (std::size_t i = kFirstClientEntry; i < entries.size(); ++i) {
      const auto found = clients.find(client_of_entry[i - kFirstClientEntry]);
      if (found == clients.end() || entries[i].revents == 0) continue;
      detail::ClientConnection& client = *found->second;
      if (entries[i].revents & POLLOUT) client.flush();
      if (entries[i].revents & (POLLIN | POLLHUP | POLLERR)) client.receive();
      ready.push_back(client.id());
    }
    applyReplies();
    serveReadyClients();
    checkClientTimers();
    closeClosingClients();
  }
}

void RobotServer::Impl::applyCodecChange() {
  robot::CodecParams codec_now;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (codec_changes == codec_changes_applied) return;
    codec_changes_applied = codec_changes;
    codec_now = codec;
  }
  for (auto& entry : clients) entry.second->switchCodec(codec_now);
  core::componentLogger("robot")->info(
      "robot codec now {} framing, {}: applied to the {} connected client(s) from their next request",
      codec_now.framing == robot::Framing::Ascii ? "ascii" : "binary", core::orientationName(codec_now.orientation),
      clients.size());
}

std::vector<pollfd> RobotServer::Impl::pollSet(std::vector<ClientId>& client_of_entry) const {
  std::vector<pollfd> entries;
  entries.push_back({wake_fd.get(), POLLIN, 0});
  const bool accepting = std::chrono::steady_clock::now() >= accept_paused_until;
  // A negative descriptor is skipped by poll(): how accepting pauses.
  entries.push_back({accepting ? listener.get() : -1, POLLIN, 0});
  for (const auto& [id, client] : clients) {
    const short events = client->hasUnsentOutput() ? (POLLIN | POLLOUT) : POLLIN;
    entries.push_back({client->fd(), events, 0});
    client_of_entry.push_back(id);
  }
  return entries;
}

int RobotServer::Impl::pollTimeoutMs() const {
  const auto now = std::chrono::steady_clock::now();
  // The earliest of: accepting resumes, a client's idle timeout, a client's log summary.
  std::optional<std::chrono::steady_clock::time_point> wake_at;
  if (now < accept_paused_until) wake_at = accept_paused_until;
  for (const auto& entry : clients) {
    const auto deadline = entry.second->nextDeadline();
    if (deadline && (!wake_at || *deadline < *wake_at)) wake_at = deadline;
  }
  if (!wake_at) return -1;
  if (*wake_at <= now) return 0;
  const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(*wake_at - now).count();
  // One more millisecond: poll() may not return before the deadline, rounded down, has passed.
  return static_cast<int>(std::min<long long>(wait, std::numeric_limits<int>::max() - 1)) + 1;
}

void RobotServer::Impl::acceptClients() {
  for (int attempt = 0; attempt < kAcceptBatch; ++attempt) {
    sockaddr_in peer{};
    detail::UniqueFd socket = detail::acceptClient(listener.get(), peer);
    if (socket.valid()) {
      admit(std::move(socket), peer);
      continue;
    }
    const int error_number = errno;
    if (error_number == EAGAIN || error_number == EWOULDBLOCK) return;
    if (isFatalAcceptError(error_number)) {
      throw core::Error("robot server: accept failed: " + detail::errnoText(error_number));
    }
    if (isOutOfResources(error_number)) {
      core::componentLogger("robot")->warn("cannot accept a connection: {}; pausing {} ms",
                                           detail::errnoText(error_number), kAcceptPause.count());
      accept_paused_until = std::chrono::steady_clock::now() + kAcceptPause;
      return;
    }
    // A connection that failed before it was accepted (ECONNABORTED, network errors): the next.
  }
}

void RobotServer::Impl::admit(detail::UniqueFd socket, const sockaddr_in& peer) {
  const std::string peer_text = core::addressText(peer.sin_addr) + ":" + std::to_string(ntohs(peer.sin_port));
  std::shared_ptr<const core::AddressFilter> filter;
  robot::CodecParams codec_now;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    filter = allowed;
    codec_now = codec;
  }
  const auto log = core::componentLogger("robot");
  if (!filter->allows(peer.sin_addr)) {
    log->warn("refused {}: not in allowed_clients", peer_text);
    return;  // the socket closes here
  }
  if (clients.size() >= static_cast<std::size_t>(max_clients) && !makeRoomFor(peer_text)) {
    log->warn("refused {}: all {} clients have a request outstanding (max_clients)", peer_text, clients.size());
    return;
  }
  detail::setNoDelay(socket.get());
  if (keepalive.idle_s > 0 &&
      !detail::setKeepAlive(socket.get(), keepalive.idle_s, keepalive.interval_s, keepalive.count)) {
    log->warn("client from {}: cannot enable TCP keepalive: {}", peer_text, detail::errnoText(errno));
  }
  const ClientId id = next_id++;
  clients.emplace(id, std::make_unique<detail::ClientConnection>(id, std::move(socket), peer_text, codec_now, limits));
  client_count.store(clients.size());
  {
    const std::lock_guard<std::mutex> lock(mutex);
    connected[id] = ConnectedClient{id, peer_text, std::chrono::system_clock::now()};
  }
  log->info("client {} connected from {}", id, peer_text);
}

bool RobotServer::Impl::makeRoomFor(const std::string& newcomer) {
  // A robot waiting for a reply keeps its slot; of the others, the one silent longest goes (a
  // controller that was switched off without closing, or a connection that never said anything).
  auto victim = clients.end();
  for (auto it = clients.begin(); it != clients.end(); ++it) {
    if (it->second->hasRequestOutstanding()) continue;
    if (victim == clients.end() || it->second->idleSince() < victim->second->idleSince()) victim = it;
  }
  if (victim == clients.end()) return false;
  detail::ClientConnection& client = *victim->second;
  const double idle_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - client.idleSince()).count();
  core::componentLogger("robot")->warn(
      "max_clients ({}) connected: closing client {} ({}), idle for {:.1f} s without a request outstanding, to "
      "make room for {}",
      max_clients, client.id(), client.peer(), idle_s, newcomer);
  client.markClosing("closed to make room for " + newcomer + " (max_clients; the longest idle)");
  closeClient(victim);
  return true;
}

}  // namespace binpick::robot
