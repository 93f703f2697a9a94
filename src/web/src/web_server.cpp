#include "binpick/web/web_server.hpp"

#include <sys/socket.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <thread>

#include "binpick/core/component_logger.hpp"
#include "binpick/core/error.hpp"
#include "bounded_task_queue.hpp"
#include "routes.hpp"

namespace binpick::web {
namespace {

// Connections that may wait for a thread beyond those served: a browser opens a few at once.
constexpr std::size_t kWaitingConnections = 8;
constexpr std::size_t kKeepAliveRequests = 20;  // then a browser's connection is closed: slots turn over
constexpr std::size_t kMaxRequestBody = 1024;   // a read-only API takes no bodies

// SO_REUSEADDR only: httplib's default also sets SO_REUSEPORT, with which a second process could
// bind the same port and take half the connections instead of failing to start.
void reuseAddressOnly(socket_t socket) {
  const int yes = 1;
  setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
}

}  // namespace

struct WebServer::Impl {
  httplib::Server server;
  std::shared_ptr<std::atomic<bool>> stopping = std::make_shared<std::atomic<bool>>(false);
  std::thread listening;
  int port = 0;
};

WebServer::WebServer(const cell::WebViewConfig& config, WebSources sources) : impl_(std::make_unique<Impl>()) {
  config.validate();
  if (!sources.cell) throw core::Error("web view: no cell report to show");
  auto context = std::make_shared<detail::RouteContext>(
      detail::RouteContext{std::move(sources), core::AddressFilter(config.allowed_clients, "web.allowed_clients")});
  httplib::Server& server = impl_->server;
  const auto threads = static_cast<std::size_t>(config.threads);
  const auto stopping = impl_->stopping;
  server.new_task_queue = [threads, stopping] {
    return new detail::BoundedTaskQueue(threads, kWaitingConnections, stopping);
  };
  const auto timeout = std::chrono::milliseconds(config.timeout_ms);
  server.set_read_timeout(timeout);
  server.set_write_timeout(timeout);
  server.set_keep_alive_timeout(std::max<time_t>(1, config.timeout_ms / 1000));
  server.set_keep_alive_max_count(kKeepAliveRequests);
  server.set_payload_max_length(kMaxRequestBody);
  server.set_socket_options(reuseAddressOnly);
  server.set_default_headers({
      {"Cache-Control", "no-store"},
      {"X-Content-Type-Options", "nosniff"},
      {"X-Frame-Options", "DENY"},
      {"Referrer-Policy", "no-referrer"},
      // The page is self-contained: its inline style and script, images and requests from here.
      {"Content-Security-Policy",
       "default-src 'none'; style-src 'unsafe-inline'; script-src 'unsafe-inline'; img-src 'self'; "
       "connect-src 'self'; base-uri 'none'; form-action 'none'; frame-ancestors 'none'"},
  });
  detail::installRoutes(server, context);

  errno = 0;
  const bool bound = config.port == 0 ? (impl_->port = server.bind_to_any_port(config.bind_address)) > 0
                                      : server.bind_to_port(config.bind_address, config.port);
  if (!bound) {
    const int error = errno;
    throw core::Error("web view: cannot listen on " + config.bind_address + ":" + std::to_string(config.port) +
                      (error != 0 ? ": " + std::string(std::strerror(error)) : ""));
  }
  if (config.port != 0) impl_->port = config.port;
  impl_->listening = std::thread([this] { impl_->server.listen_after_bind(); });
  core::componentLogger("web")->info("web view on http://{}:{}/", config.bind_address, impl_->port);
}

WebServer::~WebServer() { stop(); }

int WebServer::port() const { return impl_->port; }

void WebServer::stop() {
  if (!impl_->listening.joinable()) return;
  impl_->stopping->store(true);
  impl_->server.stop();
  impl_->listening.join();
}

}  // namespace binpick::web
