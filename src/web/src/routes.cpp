#include "routes.hpp"

#include <filesystem>
#include <fstream>

#include "binpick/cell/artefact_store.hpp"
#include "binpick/core/component_logger.hpp"
#include "page.hpp"
#include "status_json.hpp"

namespace binpick::web::detail {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kAllowed = "GET, HEAD";
// Digits only: a cycle number can never name a path (no "..", no slash, encoded or not).
const char* const kCycleFile = R"(/api/cycles/([0-9]{1,19})/(overlay\.png|cloud\.ply))";
const char* const kLatestOverlay = "/api/cycles/latest/overlay.png";

void sendJson(HttpResponse& response, const json& body, int status = 200) {
  response.status = status;
  response.body = body.dump();
  response.content_type = "application/json";
}

void sendError(HttpResponse& response, int status, const std::string& message) {
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
bool sendFile(HttpResponse& response, const fs::path& path) {
  auto stream = std::make_shared<std::ifstream>(path, std::ios::binary);
  if (!isPlainFile(path) || !*stream) return false;
  stream->seekg(0, std::ios::end);
  const std::streamoff size = stream->tellg();
  stream->seekg(0);
  if (size < 0) return false;
  response.headers.emplace_back("Content-Disposition", "inline; filename=\"" + path.filename().string() + "\"");
  response.content_type = contentTypeOf(path.filename().string());
  response.streamed_length = static_cast<std::size_t>(size);
  response.stream = [stream](std::size_t offset, std::size_t length, const BodyWriter& write) {
    char buffer[65536];
    stream->seekg(static_cast<std::streamoff>(offset));
    const std::size_t want = std::min(length, sizeof buffer);
    stream->read(buffer, static_cast<std::streamsize>(want));
    const std::streamsize got = stream->gcount();
    if (got <= 0) return false;  // the file shrank: end the response
    return write(buffer, static_cast<std::size_t>(got));
  };
  return true;
}

void serveCycleFile(const RouteContext& context, const HttpRequest& request, HttpResponse& response) {
  const uint64_t cycle = std::stoull(request.matches.at(1));  // at most 19 digits: fits
  const std::string& file = request.matches.at(2);
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

void serveLatestOverlay(const RouteContext& context, HttpResponse& response) {
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
bool screen(const RouteContext& context, const HttpRequest& request, HttpResponse& response) {
  if (!context.allowed.allows(request.remote_addr)) {
    core::componentLogger("web")->debug("refused {}: not in web.allowed_clients", request.remote_addr);
    sendError(response, 403, "this address is not in web.allowed_clients");
    return true;
  }
  if (request.method != "GET" && request.method != "HEAD") {
    response.headers.emplace_back("Allow", kAllowed);
    response.headers.emplace_back("Connection", "close");  // its body, if any, is not read
    sendError(response, 405, "the web view is read-only: " + std::string(kAllowed) + " only");
    return true;
  }
  return false;
}

}  // namespace

void installRoutes(HttpServerSettings& settings, std::shared_ptr<const RouteContext> context) {
  settings.screen = [context](const HttpRequest& request, HttpResponse& response) {
    return screen(*context, request, response);
  };
  settings.routes = {
      {"/",
       [](const HttpRequest&, HttpResponse& response) {
         response.body = std::string(indexHtml());
         response.content_type = "text/html; charset=utf-8";
       }},
      {"/api/status", [context](const HttpRequest&, HttpResponse& response) { sendJson(response, status(*context)); }},
      {"/api/cycles",
       [context](const HttpRequest&, HttpResponse& response) {
         const auto report = context->sources.cell();
         sendJson(response, cyclesJson(*report, savedCycles(*report)));
       }},
      {kLatestOverlay,
       [context](const HttpRequest&, HttpResponse& response) { serveLatestOverlay(*context, response); }},
      {kCycleFile,
       [context](const HttpRequest& request, HttpResponse& response) { serveCycleFile(*context, request, response); }},
  };
  // Unknown paths, bad requests: a JSON body saying so (the transport leaves it empty).
  settings.on_error = [](HttpResponse& response) { sendError(response, response.status, reasonOf(response.status)); };
  settings.on_exception = [](const std::string& what, HttpResponse& response) {
    core::componentLogger("web")->error("request failed: {}", what);
    sendError(response, 500, "internal error");
  };
}

}  // namespace binpick::web::detail
