#include "binpick/web/web_server.hpp"

#include "binpick/core/component_logger.hpp"
#include "binpick/core/error.hpp"
#include "binpick/core/plugin.hpp"
#include "http_transport_abi.hpp"
#include "routes.hpp"

namespace binpick::web {
namespace {

// Connections that may wait for a thread beyond those served: a browser opens a few at once.
constexpr std::size_t kWaitingConnections = 8;
constexpr std::size_t kKeepAliveRequests = 20;  // then a browser's connection is closed: slots turn over
constexpr std::size_t kMaxRequestBody = 1024;   // a read-only API takes no bodies

// Loaded by the first web view of the process, never unloaded.
const detail::HttpTransport& transport() {
  return core::loadPlugin<detail::HttpTransport>(BINPICK_HTTP_TRANSPORT_BESIDE_PROGRAM, BINPICK_HTTP_TRANSPORT_IN_BUILD,
                                                 detail::kHttpTransportEntry, detail::kHttpTransportVersion,
                                                 "web view: binpick's HTTP transport plugin");
}

detail::HttpServerSettings settingsFor(const cell::WebViewConfig& config) {
  detail::HttpServerSettings settings;
  settings.bind_address = config.bind_address;
  settings.port = config.port;
  settings.threads = static_cast<std::size_t>(config.threads);
  settings.waiting_connections = kWaitingConnections;
  settings.keep_alive_requests = kKeepAliveRequests;
  settings.max_request_body = kMaxRequestBody;
  settings.timeout_ms = config.timeout_ms;
  settings.default_headers = {
      {"Cache-Control", "no-store"},
      {"X-Content-Type-Options", "nosniff"},
      {"X-Frame-Options", "DENY"},
      {"Referrer-Policy", "no-referrer"},
      // The page is self-contained: its inline style and script, images and requests from here.
      {"Content-Security-Policy",
       "default-src 'none'; style-src 'unsafe-inline'; script-src 'unsafe-inline'; img-src 'self'; "
       "connect-src 'self'; base-uri 'none'; form-action 'none'; frame-ancestors 'none'"},
  };
  return settings;
}

}  // namespace

struct WebServer::Impl {
  const detail::HttpTransport* transport = nullptr;
  void* server = nullptr;
  int port = 0;
};

WebServer::WebServer(const cell::WebViewConfig& config, WebSources sources) : impl_(std::make_unique<Impl>()) {
  config.validate();
  if (!sources.cell) throw core::Error("web view: no cell report to show");
  auto context = std::make_shared<detail::RouteContext>(
      detail::RouteContext{std::move(sources), core::AddressFilter(config.allowed_clients, "web.allowed_clients")});
  detail::HttpServerSettings settings = settingsFor(config);
  detail::installRoutes(settings, context);
  impl_->transport = &transport();
  std::string error;
  impl_->server = impl_->transport->start(settings, impl_->port, error);
  if (impl_->server == nullptr) throw core::Error("web view: " + error);
  core::componentLogger("web")->info("web view on http://{}:{}/", config.bind_address, impl_->port);
}

WebServer::~WebServer() { stop(); }

int WebServer::port() const { return impl_->port; }

void WebServer::stop() {
  if (impl_->server == nullptr) return;
  impl_->transport->stop(impl_->server);
  impl_->server = nullptr;
}

}  // namespace binpick::web
