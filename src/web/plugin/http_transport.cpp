// The HTTP transport plugin: cpp-httplib's server behind the table of http_transport_abi.hpp.
// Requests and answers are copied between httplib's types and the table's, so that nothing of
// httplib (nor OpenSSL, which it links) reaches the programs.
#include <sys/socket.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <exception>
#include <memory>
#include <thread>

#include "bounded_task_queue.hpp"
#include "http_transport_abi.hpp"

namespace binpick::web::detail {
namespace {

// SO_REUSEADDR only: httplib's default also sets SO_REUSEPORT, with which a second process could
// bind the same port and take half the connections instead of failing to start.
void reuseAddressOnly(socket_t socket) {
  const int yes = 1;
  setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
}

HttpRequest requestOf(const httplib::Request& request) {
  HttpRequest copy{request.method, request.path, request.remote_addr, {}};
  for (const auto& match : request.matches) copy.matches.push_back(match.str());
  return copy;
}

void answer(const HttpResponse& from, httplib::Response& to) {
  to.status = from.status;
  for (const auto& [name, value] : from.headers) to.set_header(name, value);
  if (from.stream) {
    const auto provide = [stream = from.stream](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
      return stream(offset, length, [&sink](const char* data, std::size_t size) { return sink.write(data, size); });
    };
    to.set_content_provider(from.streamed_length, from.content_type, provide);
  } else if (!from.content_type.empty()) {
    to.set_content(from.body, from.content_type);
  }
}

std::string whatOf(const std::exception_ptr& error) {
  try {
    if (error) std::rethrow_exception(error);
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
  }
  return "unknown error";
}

struct Server {
  httplib::Server http;
  std::shared_ptr<std::atomic<bool>> stopping = std::make_shared<std::atomic<bool>>(false);
  std::thread listening;
};

void setLimits(Server& server, const HttpServerSettings& settings) {
  httplib::Server& http = server.http;
  const std::size_t threads = settings.threads, waiting = settings.waiting_connections;
  const auto stopping = server.stopping;
  http.new_task_queue = [threads, waiting, stopping] { return new BoundedTaskQueue(threads, waiting, stopping); };
  const auto timeout = std::chrono::milliseconds(settings.timeout_ms);
  http.set_read_timeout(timeout);
  http.set_write_timeout(timeout);
  http.set_keep_alive_timeout(std::max<time_t>(1, settings.timeout_ms / 1000));
  http.set_keep_alive_max_count(settings.keep_alive_requests);
  http.set_payload_max_length(settings.max_request_body);
  http.set_socket_options(reuseAddressOnly);
  httplib::Headers headers;
  for (const auto& [name, value] : settings.default_headers) headers.emplace(name, value);
  http.set_default_headers(std::move(headers));
}

void setHandlers(httplib::Server& http, const HttpServerSettings& settings) {
  http.set_pre_routing_handler(
      [screen = settings.screen](const httplib::Request& request, httplib::Response& response) {
        HttpResponse screened;
        if (!screen || !screen(requestOf(request), screened)) return httplib::Server::HandlerResponse::Unhandled;
        answer(screened, response);
        return httplib::Server::HandlerResponse::Handled;
      });
  for (const HttpRoute& route : settings.routes) {
    http.Get(route.pattern, [handler = route.handler](const httplib::Request& request, httplib::Response& response) {
      HttpResponse answered;
      handler(requestOf(request), answered);
      answer(answered, response);
    });
  }
  http.set_error_handler([on_error = settings.on_error](const httplib::Request&, httplib::Response& response) {
    if (!response.body.empty() || !on_error) return;  // the route's own answer says why
    HttpResponse error;
    error.status = response.status;
    on_error(error);
    answer(error, response);
  });
  http.set_exception_handler([on_exception = settings.on_exception](
                                 const httplib::Request&, httplib::Response& response, std::exception_ptr error) {
    HttpResponse failed;
    failed.status = 500;
    if (on_exception) on_exception(whatOf(error), failed);
    answer(failed, response);
  });
}

void* start(const HttpServerSettings& settings, int& port, std::string& error) {
  try {
    auto server = std::make_unique<Server>();
    setLimits(*server, settings);
    setHandlers(server->http, settings);
    errno = 0;
    port = settings.port;
    const bool bound = settings.port == 0 ? (port = server->http.bind_to_any_port(settings.bind_address)) > 0
                                          : server->http.bind_to_port(settings.bind_address, settings.port);
    if (!bound) {
      const int reason = errno;
      error = "cannot listen on " + settings.bind_address + ":" + std::to_string(settings.port) +
              (reason != 0 ? ": " + std::string(std::strerror(reason)) : "");
      return nullptr;
    }
    Server* running = server.release();
    running->listening = std::thread([running] { running->http.listen_after_bind(); });
    return running;
  } catch (const std::exception& e) {
    error = e.what();
    return nullptr;
  }
}

void stop(void* handle) {
  auto* server = static_cast<Server*>(handle);
  if (server == nullptr) return;
  server->stopping->store(true);
  server->http.stop();
  if (server->listening.joinable()) server->listening.join();
  delete server;
}

const HttpTransport kTransport{kHttpTransportVersion, start, stop};

}  // namespace
}  // namespace binpick::web::detail

extern "C" const binpick::web::detail::HttpTransport* binpick_http_transport() {
  return &binpick::web::detail::kTransport;
}
