#include "routes.hpp"

#include <filesystem>
#include <fstream>

#include "binpick/cell/artefact_store.hpp"
#include "binpick/core/component_logger.hpp"
#include "status_json.hpp"
#include "page.hpp"

namespace binpick::web::detail {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kAllowed = "GET, HEAD";
// Digits only: a cycle number can never name a path (no "..", no slash, encoded or not).
const char* const kCycleFile = R"(/api/cycles/([0-9]{1,19})/(overlay\.png|cloud\.ply))";
const char* const kLatestOverlay = "/api/cycles/latest/overlay.png";

void sendJson(httplib::Response& response, const json& body, int status = 200) {
  response.status = status;
  response.set_content(body.dump(), "application/json");
}

void sendError(httplib::Response& response, int status, const std::string& message) {
  sendJson(response, {{"error", message}, {"status", status}}, status);
}

std::vector<cell::SavedCycleDirectory> savedCycles(const cell::CellReport& report) {
  if (!report.artefact_directory) return {};
  return cell::savedCycleDirectories(*report.artefact_directory);
}

const char* contentTypeOf(const std::string& file) {
  return file == "overlay.png" ? "image/png" : "application/octet-stream";
}

// A regular file inside a saved cycle directory, never a symlink out of it.
bool isPlainFile(const fs::path& path) {
  std::error_code error;
  return fs::is_regular_file(fs::symlink_status(path, error));
}

// Streams `path` (opened now: a cycle deleted meanwhile still sends whole).
bool sendFile(httplib::Response& response, const fs::path& path) {
  auto stream = std::make_shared<std::ifstream>(path, std::ios::binary);
  if (!isPlainFile(path) || !*stream) return false;
  stream->seekg(0, std::ios::end);
  const std::streamoff size = stream->tellg();
  stream->seekg(0);
  if (size < 0) return false;
  response.set_header("Content-Disposition", "inline; filename=\"" + path.filename().string() + "\"");
  response.set_content_provider(static_cast<std::size_t>(size), contentTypeOf(path.filename().string()),
                                [stream](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
                                  char buffer[65536];
                                  stream->seekg(static_cast<std::streamoff>(offset));
                                  const std::size_t want = std::min(length, sizeof buffer);
                                  stream->read(buffer, static_cast<std::streamsize>(want));
                                  const std::streamsize got = stream->gcount();
                                  if (got <= 0) return false;  // the file shrank: end the response
                                  return sink.write(buffer, static_cast<std::size_t>(got));
                                });
  return true;
}

void serveCycleFile(const RouteContext& context, const httplib::Request& request, httplib::Response& response) {
  const uint64_t cycle = std::stoull(request.matches[1].str());  // at most 19 digits: fits
  const std::string file = request.matches[2].str();
  const auto report = context.sources.cell();
  if (!report->artefact_directory) return sendError(response, 404, "cycles are not saved (no artefacts: section)");
  const std::vector<cell::SavedCycleDirectory> saved = savedCycles(*report);
  // Cycle numbers start again after a restart: the newest directory of that number.
  for (auto it = saved.rbegin(); it != saved.rend(); ++it) {
    if (it->cycle != cycle) continue;
    if (sendFile(response, fs::path(it->path) / file)) return;
    return sendError(response, 404, "cycle " + std::to_string(cycle) + " has no " + file + " saved");
  }
  sendError(response, 404, "cycle " + std::to_string(cycle) + " is not saved");
}

void serveLatestOverlay(const RouteContext& context, httplib::Response& response) {
  const auto report = context.sources.cell();
  const std::vector<cell::SavedCycleDirectory> saved = savedCycles(*report);
  for (auto it = saved.rbegin(); it != saved.rend(); ++it) {
    if (sendFile(response, fs::path(it->path) / "overlay.png")) return;
  }
  sendError(response, 404,
            report->artefact_directory ? "no saved cycle has an overlay yet"
                                       : "cycles are not saved (no artefacts: section)");
}

json status(const RouteContext& context) {
  const auto report = context.sources.cell();
  StatusInputs inputs{*report, {}, savedCycles(*report), {}, std::chrono::system_clock::now()};
  if (context.sources.robots) inputs.robots = context.sources.robots();
  if (context.sources.log) inputs.log = context.sources.log->last(kPageLogLines);
  return statusJson(inputs);
}

std::string reasonOf(int status) {
  switch (status) {
    case 400: return "bad request";
    case 404: return "no such page or API";
    case 413: return "request too large";
    case 414: return "request line too long";
    default: return "HTTP status " + std::to_string(status);
  }
}

// Before routing: the allow-list, then the method. Anything but GET and HEAD is refused here,
// before a body is read.
httplib::Server::HandlerResponse screen(const RouteContext& context, const httplib::Request& request,
                                        httplib::Response& response) {
  if (!context.allowed.allows(request.remote_addr)) {
    core::componentLogger("web")->debug("refused {}: not in web.allowed_clients", request.remote_addr);
    sendError(response, 403, "this address is not in web.allowed_clients");
    return httplib::Server::HandlerResponse::Handled;
  }
  if (request.method != "GET" && request.method != "HEAD") {
    response.set_header("Allow", kAllowed);
    response.set_header("Connection", "close");  // its body, if any, is not read
    sendError(response, 405, "the web view is read-only: " + std::string(kAllowed) + " only");
    return httplib::Server::HandlerResponse::Handled;
  }
  return httplib::Server::HandlerResponse::Unhandled;
}

}  // namespace

void installRoutes(httplib::Server& server, std::shared_ptr<const RouteContext> context) {
  server.set_pre_routing_handler([context](const httplib::Request& request, httplib::Response& response) {
    return screen(*context, request, response);
  });
  server.Get("/", [](const httplib::Request&, httplib::Response& response) {
    const std::string_view page = indexHtml();
    response.set_content(page.data(), page.size(), "text/html; charset=utf-8");
  });
  server.Get("/api/status",
             [context](const httplib::Request&, httplib::Response& response) { sendJson(response, status(*context)); });
  server.Get("/api/cycles", [context](const httplib::Request&, httplib::Response& response) {
    const auto report = context->sources.cell();
    sendJson(response, cyclesJson(*report, savedCycles(*report)));
  });
  server.Get(kLatestOverlay, [context](const httplib::Request&, httplib::Response& response) {
    serveLatestOverlay(*context, response);
  });
  server.Get(kCycleFile, [context](const httplib::Request& request, httplib::Response& response) {
    serveCycleFile(*context, request, response);
  });
  // Unknown paths, bad requests: a JSON body saying so (httplib leaves it empty).
  server.set_error_handler([](const httplib::Request&, httplib::Response& response) {
    if (!response.body.empty()) return;  // ours already say why
    sendError(response, response.status, reasonOf(response.status));
  });
  server.set_exception_handler([](const httplib::Request&, httplib::Response& response, std::exception_ptr error) {
    std::string what = "internal error";
    try {
      if (error) std::rethrow_exception(error);
    } catch (const std::exception& e) {
      what = e.what();
    } catch (...) {
    }
    core::componentLogger("web")->error("request failed: {}", what);
    sendError(response, 500, "internal error");
  });
}

}  // namespace binpick::web::detail
