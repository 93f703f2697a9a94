#pragma once
// Internal: the web view's routes on an httplib server (web_server.hpp lists them).
#include "httplib.hpp"

#include <memory>

#include "binpick/core/address_filter.hpp"
#include "binpick/web/web_server.hpp"

namespace binpick::web::detail {

struct RouteContext {
  WebSources sources;
  core::AddressFilter allowed;
};

void installRoutes(httplib::Server& server, std::shared_ptr<const RouteContext> context);

}  // namespace binpick::web::detail
