#pragma once
// The web view of a cell: one self-contained page (no external assets) and a read-only JSON API
// over HTTP, served by cpp-httplib on threads of its own (docs/binpickd.md, "Web view"):
//   GET /                                  the page; it polls /api/status every second
//   GET /api/status                        state, cycle, recipe, source, robots, uptime, last cycle, log
//   GET /api/cycles                        the recent cycles: number, time, status, counts, stage times
//   GET /api/cycles/<n|latest>/overlay.png a saved cycle's overlay
//   GET /api/cycles/<n>/cloud.ply          a saved cycle's cloud
// Errors are JSON ({"error": "..."}): 404 for an unknown path or a cycle or file not saved, 405
// (with Allow: GET, HEAD) for any other method, 403 for a client outside allowed_clients. Files
// are only ever read from the saved cycle directories (<n> is digits only).
//
// No HTTP client can delay the cell: requests only copy the cell's published report
// (CellService::report()); at most `threads` connections are served at once, each dropped after
// timeout_ms without progress, and while all threads are busy and a few connections wait, new
// ones wait in the kernel's backlog rather than in memory.
//
// Thread-safety: port() any time; stop() from one thread; the destructor stops.
#include <functional>
#include <memory>
#include <vector>

#include "binpick/cell/cell_config.hpp"
#include "binpick/cell/cell_report.hpp"
#include "binpick/robot/robot_server.hpp"
#include "binpick/web/log_ring.hpp"

namespace binpick::web {

// Where the page's content comes from; each is called on the web server's threads.
struct WebSources {
  std::function<std::shared_ptr<const cell::CellReport>()> cell;  // required
  std::function<std::vector<robot::ConnectedClient>()> robots;    // none: no robots listed
  std::shared_ptr<const LogRing> log;                             // none: no log lines
};

constexpr std::size_t kPageLogLines = 30;  // log lines /api/status carries

class WebServer {
 public:
  // Validates `config`, binds and starts serving. Throws core::Error naming the address and port
  // when it cannot listen ("web view: cannot listen on 127.0.0.1:8080: Address already in use"),
  // or naming the HTTP transport plugin (loaded by the first web view) when it cannot be loaded.
  WebServer(const cell::WebViewConfig& config, WebSources sources);
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  int port() const;
  // Stops accepting, finishes the requests under way (each bounded by timeout_ms) and joins the
  // threads. Idempotent.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace binpick::web
