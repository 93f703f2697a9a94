#include "web_client.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <regex>
#include <stdexcept>

#include <httplib.h>

namespace binpick::web::testing {
namespace {

using Clock = std::chrono::steady_clock;

int connectLoopback(int port) {
  const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (fd < 0 || connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
    if (fd >= 0) close(fd);
    throw std::runtime_error("cannot connect to the web view on port " + std::to_string(port));
  }
  return fd;
}

}  // namespace

std::string HttpReply::header(const std::string& name) const {
  const auto it = headers.find(name);
  return it == headers.end() ? "" : it->second;
}

HttpReply httpRequest(int port, const std::string& method, const std::string& path) {
  httplib::Client client("127.0.0.1", port);
  client.set_connection_timeout(std::chrono::seconds(30));
  client.set_read_timeout(std::chrono::seconds(60));
  const auto send = [&]() -> httplib::Result {
    if (method == "GET") return client.Get(path);
    if (method == "HEAD") return client.Head(path);
    if (method == "POST") return client.Post(path, "x=1", "application/x-www-form-urlencoded");
    if (method == "PUT") return client.Put(path, "{}", "application/json");
    if (method == "PATCH") return client.Patch(path, "{}", "application/json");
    if (method == "DELETE") return client.Delete(path);
    if (method == "OPTIONS") return client.Options(path);
    throw std::invalid_argument("unknown method " + method);
  };
  const httplib::Result result = send();
  HttpReply reply;
  if (!result) return reply;
  reply.status = result->status;
  reply.body = result->body;
  for (const auto& [key, value] : result->headers) reply.headers.emplace(key, value);
  return reply;
}

std::string rawExchange(int port, const std::string& request, std::chrono::milliseconds timeout) {
  const int fd = connectLoopback(port);
  send(fd, request.data(), request.size(), MSG_NOSIGNAL);
  std::string response;
  const auto deadline = Clock::now() + timeout;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    pollfd p{fd, POLLIN, 0};
    if (left <= 0 || poll(&p, 1, static_cast<int>(left)) <= 0) break;
    char buffer[4096];
    const ssize_t n = recv(fd, buffer, sizeof buffer, 0);
    if (n <= 0) break;
    response.append(buffer, static_cast<std::size_t>(n));
  }
  close(fd);
  return response;
}

int statusOf(const std::string& response) {
  std::smatch match;
  static const std::regex status_line(R"(^HTTP/1\.[01] ([0-9]{3}))");
  return std::regex_search(response, match, status_line) ? std::stoi(match[1].str()) : 0;
}

StalledClient::StalledClient(int port, const std::string& bytes) : fd_(connectLoopback(port)) {
  // A tiny receive buffer: the server's replies pile up on its side, as with a client that
  // stopped reading.
  const int small = 1024;
  setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
  if (!bytes.empty()) send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL);
}

StalledClient::~StalledClient() { close(fd_); }

int webPortFromLog(const std::string& log) {
  std::smatch match;
  static const std::regex line(R"(web view on http://[0-9.]+:([0-9]+)/)");
  return std::regex_search(log, match, line) ? std::stoi(match[1].str()) : 0;
}

}  // namespace binpick::web::testing
