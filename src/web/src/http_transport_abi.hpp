#pragma once
// What the HTTP transport plugin (plugin/http_transport.cpp) hands to web_server.cpp: an HTTP/1.1
// server on threads of its own, served with cpp-httplib, behind one table of functions found by a
// C name (binpick/core/plugin.hpp). The web view's routes and answers stay in routes.cpp; only the
// plugin links cpp-httplib and, through it, OpenSSL, whose loading and initialisation every start
// of every program paid before (2.5 ms of `binpick detect`'s 14 ms start). Both sides compile this
// header in the same build; the version refuses a plugin left from another build.
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace binpick::web::detail {

inline constexpr int kHttpTransportVersion = 1;
inline constexpr const char* kHttpTransportEntry = "binpick_http_transport";

struct HttpRequest {
  std::string method, path, remote_addr;
  std::vector<std::string> matches;  // the route pattern's groups, [0] the whole path
};

// Writes the next piece of a streamed body; false when the client is gone.
using BodyWriter = std::function<bool(const char* data, std::size_t size)>;

struct HttpResponse {
  int status = 200;
  std::string content_type;  // empty: no body
  std::string body;
  std::vector<std::pair<std::string, std::string>> headers;
  // Set: the body is streamed instead, `streamed_length` bytes asked for a range at a time
  // (offset, length); false ends the response.
  std::function<bool(std::size_t offset, std::size_t length, const BodyWriter& write)> stream;
  std::size_t streamed_length = 0;
};

using HttpHandler = std::function<void(const HttpRequest&, HttpResponse&)>;

struct HttpRoute {
  std::string pattern;  // a regular expression matching the whole path; GET and HEAD
  HttpHandler handler;
};

struct HttpServerSettings {
  std::string bind_address;
  int port = 0;                         // 0: any free port
  std::size_t threads = 1;              // connections served at once
  std::size_t waiting_connections = 0;  // accepted connections waiting for a thread, at most
  std::size_t keep_alive_requests = 1;  // requests on one connection before it is closed
  std::size_t max_request_body = 0;     // bytes
  int timeout_ms = 1000;                // read, write and keep-alive
  std::vector<std::pair<std::string, std::string>> default_headers;
  // Before routing, every request: true when it answered (the request goes no further).
  std::function<bool(const HttpRequest&, HttpResponse&)> screen;
  std::vector<HttpRoute> routes;
  // An answer of status >= 400 without a body (no route, a malformed request): the body.
  std::function<void(HttpResponse&)> on_error;
  // A handler threw `what`: the answer.
  std::function<void(const std::string& what, HttpResponse&)> on_exception;
};

// None of the functions throws.
struct HttpTransport {
  int version;
  // Binds and serves; the bound port in `port`. Null, with why in `error` ("cannot listen on
  // ADDRESS:PORT: REASON"), when it cannot listen.
  void* (*start)(const HttpServerSettings& settings, int& port, std::string& error);
  // Stops accepting, finishes the requests under way, joins the threads and frees the server.
  void (*stop)(void* server);
};

}  // namespace binpick::web::detail

extern "C" const binpick::web::detail::HttpTransport* binpick_http_transport();
