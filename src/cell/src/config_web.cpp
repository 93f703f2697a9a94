// The `web:` section: the web view's address, allow-list and limits (binpick::web serves it).
#include <arpa/inet.h>

#include "binpick/core/address_filter.hpp"
#include "config_sections.hpp"

namespace binpick::cell {

std::optional<WebViewConfig> readWebView(core::YamlSection s) {
  if (s.isNull()) return std::nullopt;  // no section: no web view
  WebViewConfig web;
  s.read("bind_address", web.bind_address);
  s.read("port", web.port);
  s.read("allowed_clients", web.allowed_clients);
  s.read("threads", web.threads);
  s.read("timeout_ms", web.timeout_ms);
  s.finish();
  return web;
}

void WebViewConfig::validate() const {
  const std::string owner = "web";
  in_addr address{};
  core::requireField(inet_pton(AF_INET, bind_address.c_str(), &address) == 1, owner, "bind_address", "an IPv4 address",
                     bind_address);
  core::requireField(port >= 0 && port <= 65535, owner, "port", "in [0, 65535]", port);
  core::AddressFilter{allowed_clients, owner + ".allowed_clients"};  // parsing is the check
  core::requireField(threads >= 1 && threads <= 64, owner, "threads", "in [1, 64]", threads);
  core::requireField(timeout_ms >= 100 && timeout_ms <= 600000, owner, "timeout_ms", "in [100, 600000]", timeout_ms);
}

}  // namespace binpick::cell
