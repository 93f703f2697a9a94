#pragma once
// Test support: HTTP requests to the web view, through cpp-httplib's client and through raw
// sockets for what a client library would not send (paths as typed, half requests, no reading).
#include <chrono>
#include <map>
#include <string>

namespace binpick::web::testing {

struct HttpReply {
  int status = 0;  // 0: no answer
  std::string body;
  std::multimap<std::string, std::string> headers;
  std::string header(const std::string& name) const;  // "" when absent
};

// `method`: GET, HEAD, POST, PUT, DELETE, PATCH, OPTIONS.
HttpReply httpRequest(int port, const std::string& method, const std::string& path);
inline HttpReply httpGet(int port, const std::string& path) { return httpRequest(port, "GET", path); }

// Sends `request` as it is on a new connection and reads until the server closes it or
// `timeout` passes; returns what came back ("" for nothing).
std::string rawExchange(int port, const std::string& request, std::chrono::milliseconds timeout);
// The status code of a raw response ("HTTP/1.1 404 Not Found" -> 404), 0 when there is none.
int statusOf(const std::string& response);

// A connection that sends `bytes` and then neither sends nor reads anything until destroyed.
class StalledClient {
 public:
  StalledClient(int port, const std::string& bytes);
  ~StalledClient();
  StalledClient(const StalledClient&) = delete;
  StalledClient& operator=(const StalledClient&) = delete;

 private:
  int fd_ = -1;
};

// The web view's port from binpickd's log ("web view on http://127.0.0.1:PORT/"), 0 if not there.
int webPortFromLog(const std::string& log);

}  // namespace binpick::web::testing
