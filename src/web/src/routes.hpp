#pragma once
// Internal: the web view's routes and answers (web_server.hpp lists them), on the settings of the
// HTTP transport that serves them.
#include <memory>

#include "binpick/core/address_filter.hpp"
#include "binpick/web/web_server.hpp"
#include "http_transport_abi.hpp"

namespace binpick::web::detail {

struct RouteContext {
  WebSources sources;
  core::AddressFilter allowed;
};

// Sets the screen, the routes and the error and exception answers of `settings`.
void installRoutes(HttpServerSettings& settings, std::shared_ptr<const RouteContext> context);

}  // namespace binpick::web::detail
