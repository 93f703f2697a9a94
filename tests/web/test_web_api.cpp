// The web view of a binpickd process on the virtual cell's bin: the JSON API's shape, errors for
// what is not there or not allowed, paths that try to leave the artefact directory, clients that
// stall or stop reading while a robot runs its cycle, a port in use, and the allow-list.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "binpick/core/stopwatch.hpp"
#include "daemon_fixture.hpp"
#include "web_client.hpp"

namespace binpick::cell::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using nlohmann::json;
using robot::Command;
using robot::Status;
using web::testing::httpGet;
using web::testing::httpRequest;
using web::testing::rawExchange;
using web::testing::StalledClient;
using web::testing::statusOf;

class WebViewTest : public DaemonTest {
 protected:
  // binpickd with the web view on a free port; its overlays and clouds saved (not the captures:
  // saving 52 images would hold the cycle's files back for seconds).
  void startWithWeb(const std::string& web = "web: {bind_address: 127.0.0.1, port: 0}\n") {
    start(web + "artefacts: {directory: " + pathOf("cycles") + ", capture: false}\n");
    ASSERT_TRUE(notify_->waitFor("READY=1", 120s)) << daemonStderr();
    web_port_ = web::testing::webPortFromLog(daemonStderr());
    ASSERT_GT(web_port_, 0) << daemonStderr();
  }
  json getJson(const std::string& path) {
    const auto reply = httpGet(web_port_, path);
    EXPECT_EQ(reply.status, 200) << path << ": " << reply.body;
    EXPECT_EQ(reply.header("Content-Type"), "application/json");
    return json::parse(reply.body);
  }
  // Polls /api/status until `done(status)`; the last status either way.
  template <typename Done>
  json statusWhen(const Done& done, std::chrono::seconds patience = 120s) {
    const auto deadline = std::chrono::steady_clock::now() + patience;
    json status = getJson("/api/status");
    while (!done(status) && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(50ms);
      status = getJson("/api/status");
    }
    return status;
  }
  // TRIGGER and the first NEXT: the robot's side of a cycle.
  double robotCycleMs(RobotClient& robot) {
    const core::Stopwatch watch;
    EXPECT_EQ(robot.ask(request(Command::Trigger), 120s).status, Status::Ok);
    EXPECT_EQ(robot.ask(request(Command::NextPick), 120s).status, Status::Ok);
    return watch.elapsedMs();
  }
  json savedCycle(int number) {
    return statusWhen([&](const json& s) {
      return s["last_cycle"].is_object() && s["last_cycle"]["number"] == number &&
             !s["last_cycle"]["overlay"].is_null();
    });
  }

  int web_port_ = 0;
};

TEST_F(WebViewTest, StatusAndCyclesDescribeTheCellAndItsLastCycle) {
  startWithWeb();
  const json idle = getJson("/api/status");
  EXPECT_EQ(idle["state"], "idle");
  EXPECT_EQ(idle["cycle"], 0);
  EXPECT_EQ(idle["recipe"], "l_bracket");
  EXPECT_EQ(idle["recipes"], json({"l_bracket", "second"}));
  EXPECT_TRUE(idle["last_cycle"].is_null());
  EXPECT_EQ(idle["source"]["mode"], "replay");
  EXPECT_TRUE(idle["source"]["calibration_ok"].get<bool>());
  EXPECT_TRUE(idle["source"]["hand_eye"].get<bool>());
  EXPECT_TRUE(idle["artefacts_saved"].get<bool>());
  EXPECT_GE(idle["uptime_s"].get<double>(), 0.0);
  EXPECT_TRUE(idle["robots"].empty());
  EXPECT_EQ(getJson("/api/cycles")["cycles"], json::array());

  RobotClient robot(port_);
  ASSERT_EQ(robot.ask(request(Command::Trigger)).status, Status::Ok);
  const robot::Reply first = robot.ask(request(Command::NextPick));
  ASSERT_EQ(first.status, Status::Ok);

  const json status = savedCycle(1);
  EXPECT_EQ(status["cycle"], 1);
  EXPECT_EQ(status["state"], "waiting_for_robot") << "picks are left after the first NEXT";
  EXPECT_EQ(status["picks_waiting"], first.integers.at(0));
  ASSERT_EQ(status["robots"].size(), 1u);
  EXPECT_EQ(status["robots"][0]["peer"].get<std::string>().rfind("127.0.0.1:", 0), 0u);
  EXPECT_EQ(status["orientation"]["convention"], "quaternion");
  EXPECT_EQ(status["source"]["captures"], 1);
  const json& cycle = status["last_cycle"];
  EXPECT_EQ(cycle["status"], "ok");
  EXPECT_EQ(cycle["recipe"], "l_bracket");
  EXPECT_GT(cycle["counts"]["detected"].get<int>(), 0);
  ASSERT_GT(cycle["picks"].size(), 0u);
  EXPECT_EQ(cycle["counts"]["picks"], cycle["picks"].size());
  // Detections below limits.min_pick_coverage, named for that test (not the detector's `sure`).
  EXPECT_TRUE(cycle["counts"]["low_coverage"].is_number_unsigned());
  EXPECT_FALSE(cycle["counts"].contains("not_sure"));
  const json& pick = cycle["picks"][0];
  EXPECT_EQ(pick["order"], 1);
  EXPECT_EQ(pick["position_mm"].size(), 3u);
  EXPECT_EQ(pick["orientation"].size(), 4u);  // quaternion
  for (const char* key : {"object", "grasp", "grasp_name", "tilt_deg", "score", "coverage", "rank", "clearance_mm"}) {
    EXPECT_TRUE(pick.contains(key)) << key;
  }
  // The first pick is the one NEXT sent: its position in millimetres.
  const Eigen::Vector3d sent = first.T_base_tool->translation() * 1000.0;
  EXPECT_NEAR(pick["position_mm"][0].get<double>(), sent.x(), 0.02);
  for (const char* key : {"invalid", "avoided", "tilt", "bin", "cloud", "seal"})
    EXPECT_TRUE(cycle["rejected"].contains(key));
  for (const char* key : {"capture", "reconstruct", "detect", "plan", "total"}) {
    EXPECT_GT(cycle["timing_ms"][key].get<double>(), 0.0) << key;
  }
  EXPECT_EQ(cycle["overlay"], "/api/cycles/1/overlay.png");
  EXPECT_EQ(cycle["cloud"], "/api/cycles/1/cloud.ply");
  EXPECT_EQ(status["latest_overlay"]["cycle"], 1);
  // The log lines of every component, the cell's included.
  bool cycle_logged = false;
  for (const json& line : status["log"]) cycle_logged |= line["text"].get<std::string>().rfind("cycle 1:", 0) == 0;
  EXPECT_TRUE(cycle_logged) << status["log"].dump(1);

  const json cycles = getJson("/api/cycles")["cycles"];
  ASSERT_EQ(cycles.size(), 1u);
  for (const char* key : {"number", "time", "status", "counts", "timing_ms", "rejected", "overlay"}) {
    EXPECT_TRUE(cycles[0].contains(key)) << key;
  }
  EXPECT_FALSE(cycles[0].contains("picks")) << "the list stays small";

  const auto overlay = httpGet(web_port_, "/api/cycles/1/overlay.png");
  EXPECT_EQ(overlay.status, 200);
  EXPECT_EQ(overlay.header("Content-Type"), "image/png");
  EXPECT_EQ(overlay.body.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(httpGet(web_port_, "/api/cycles/latest/overlay.png").body, overlay.body);
  const auto cloud = httpGet(web_port_, "/api/cycles/1/cloud.ply");
  EXPECT_EQ(cloud.status, 200);
  EXPECT_EQ(cloud.body.substr(0, 4), "ply\n");
  const fs::path saved = fs::directory_iterator(pathOf("cycles"))->path();  // the one cycle directory
  EXPECT_EQ(cloud.body.size(), fs::file_size(saved / "cloud.ply"));

  const auto page = httpGet(web_port_, "/");
  EXPECT_EQ(page.status, 200);
  EXPECT_EQ(page.header("Content-Type"), "text/html; charset=utf-8");
  EXPECT_NE(page.body.find("/api/status"), std::string::npos);
  for (const char* external : {"src=\"http", "href=\"http", "src=\"//", "href=\"//", "url(http", "import "}) {
    EXPECT_EQ(page.body.find(external), std::string::npos) << "no external assets: " << external;
  }
}

TEST_F(WebViewTest, WhatIsNotThereIsA404WithAJsonError) {
  startWithWeb();
  for (const std::string path :
       {"/api/cycles/7/overlay.png", "/api/cycles/7/cloud.ply", "/api/cycles/latest/overlay.png", "/nothing",
        "/api/cycles/1/detections.json", "/api/cycles/1/capture", "/index.html"}) {
    const auto reply = httpGet(web_port_, path);
    EXPECT_EQ(reply.status, 404) << path;
    EXPECT_EQ(reply.header("Content-Type"), "application/json") << path;
    EXPECT_TRUE(json::parse(reply.body).contains("error")) << path << ": " << reply.body;
  }
}

TEST_F(WebViewTest, OtherMethodsThanGetAndHeadAre405WithAnAllowHeader) {
  startWithWeb();
  for (const std::string method : {"POST", "PUT", "DELETE", "PATCH", "OPTIONS"}) {
    for (const std::string path : {"/", "/api/status", "/api/cycles/1/overlay.png", "/nothing"}) {
      const auto reply = httpRequest(web_port_, method, path);
      EXPECT_EQ(reply.status, 405) << method << " " << path;
      EXPECT_EQ(reply.header("Allow"), "GET, HEAD") << method << " " << path;
    }
  }
  EXPECT_EQ(statusOf(rawExchange(web_port_, "TRACE / HTTP/1.1\r\nHost: x\r\n\r\n", 30s)), 405);
  EXPECT_EQ(httpRequest(web_port_, "HEAD", "/api/status").status, 200);
}

TEST_F(WebViewTest, NoPathLeavesTheArtefactDirectory) {
  startWithWeb();
  RobotClient robot(port_);
  robotCycleMs(robot);
  savedCycle(1);
  // A secret beside the artefact directory, and a cycle directory that is a symlink to it.
  std::ofstream(pathOf("secret.txt")) << "SECRET-CONTENT";
  fs::create_directories(pathOf("outside"));
  std::ofstream(pathOf("outside/overlay.png")) << "SECRET-CONTENT";
  fs::create_directory_symlink(pathOf("outside"), pathOf("cycles/cycle-000042-20300101T000000Z"));
  for (const std::string path : {
           "/api/cycles/../../etc/passwd",
           "/api/cycles/%2e%2e/%2e%2e/etc/passwd",
           "/api/cycles/1/..%2f..%2fsecret.txt",
           "/api/cycles/1%2f..%2f..%2fsecret.txt/overlay.png",
           "/api/cycles/..%2f..%2fsecret.txt",
           "/api/cycles/latest/../../secret.txt",
           "/%2e%2e/%2e%2e/%2e%2e/etc/passwd",
           "/..%5c..%5csecret.txt",
           "/api/cycles/-1/overlay.png",
           "/api/cycles/1.0/overlay.png",
           "/api/cycles/%31/../../secret.txt",
           "/api/cycles/99999999999999999999/overlay.png",
           "/api/cycles/42/overlay.png",
           "/api/cycles/1/overlay.png%00.txt",
           "//etc/passwd",
       }) {
    const std::string response =
        rawExchange(web_port_, "GET " + path + " HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n", 30s);
    const int status = statusOf(response);
    EXPECT_TRUE(status == 400 || status == 404) << path << " answered " << status;
    EXPECT_EQ(response.find("SECRET-CONTENT"), std::string::npos) << path;
    EXPECT_EQ(response.find("root:"), std::string::npos) << path;
  }
  EXPECT_EQ(statusOf(rawExchange(
                web_port_, "GET /api/cycles/1/overlay.png HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n", 30s)),
            200);
}

// A robot's TRIGGER and NEXT with and without hostile HTTP clients: half requests that stall,
// pipelined downloads never read, and more connections than the web view has threads.
TEST_F(WebViewTest, SlowAndHostileHttpClientsDoNotDelayTheRobot) {
  startWithWeb("web: {bind_address: 127.0.0.1, port: 0, threads: 2, timeout_ms: 60000}\n");
  RobotClient robot(port_);
  robotCycleMs(robot);  // warm: the model and caches
  savedCycle(1);
  const double quiet_ms = robotCycleMs(robot);

  std::vector<std::unique_ptr<StalledClient>> hostile;
  for (int i = 0; i < 4; ++i) {
    hostile.push_back(std::make_unique<StalledClient>(web_port_, "GET /api/status HTTP/1.1\r\nHost: x\r\nX-Slow: "));
  }
  std::string downloads;
  for (int i = 0; i < 50; ++i) downloads += "GET /api/cycles/1/cloud.ply HTTP/1.1\r\nHost: x\r\n\r\n";
  for (int i = 0; i < 2; ++i) hostile.push_back(std::make_unique<StalledClient>(web_port_, downloads));
  // Connected, silent: they wait for a thread, then hold it (the kernel's backlog takes the rest).
  for (int i = 0; i < 6; ++i) hostile.push_back(std::make_unique<StalledClient>(web_port_, ""));
  std::this_thread::sleep_for(200ms);  // let them take the web view's threads

  // The web view is saturated (two threads, both stuck for a minute) ...
  EXPECT_EQ(statusOf(rawExchange(web_port_, "GET /api/status HTTP/1.1\r\nHost: x\r\n\r\n", 500ms)), 0);
  // ... and the robot's cycles go on.
  double hostile_ms = 0;
  for (int i = 0; i < 3; ++i) hostile_ms = std::max(hostile_ms, robotCycleMs(robot));
  EXPECT_EQ(robot.ask(request(Command::Status), 10s).status, Status::Ok);
  std::cout << "robot TRIGGER + NEXT: " << quiet_ms << " ms without HTTP clients, at most " << hostile_ms
            << " ms beside " << hostile.size() << " hostile ones\n";
  hostile.clear();
  // Once they are gone the page answers again.
  EXPECT_EQ(getJson("/api/status")["cycle"], 5);
}

TEST_F(WebViewTest, AClientOutsideAllowedClientsIsRefused) {
  startWithWeb("web: {bind_address: 127.0.0.1, port: 0, allowed_clients: [10.0.0.0/8]}\n");
  for (const std::string path : {"/", "/api/status", "/api/cycles/latest/overlay.png"}) {
    const auto reply = httpGet(web_port_, path);
    EXPECT_EQ(reply.status, 403) << path;
    EXPECT_EQ(reply.body.find("l_bracket"), std::string::npos) << "nothing of the cell: " << reply.body;
  }
}

TEST_F(WebViewTest, AClientInAllowedClientsIsServed) {
  startWithWeb("web: {bind_address: 127.0.0.1, port: 0, allowed_clients: [10.0.0.0/8, 127.0.0.0/8]}\n");
  EXPECT_EQ(httpGet(web_port_, "/api/status").status, 200);
}

TEST_F(WebViewTest, APortInUseStopsTheStartWithOneLineNamingIt) {
  const int taken = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(bind(taken, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  ASSERT_EQ(listen(taken, 1), 0);
  socklen_t length = sizeof address;
  getsockname(taken, reinterpret_cast<sockaddr*>(&address), &length);
  const int port = ntohs(address.sin_port);

  config_path_ = pathOf("binpickd.yaml");
  std::ofstream(config_path_) << cellConfigYaml(cellScene(), "web: {port: " + std::to_string(port) + "}\n");
  DaemonOptions options;
  options.config_path = config_path_;
  options.port_file = pathOf("port");
  options.stderr_file = pathOf("stderr");
  DaemonProcess daemon(options);
  EXPECT_EQ(daemon.wait(120s), 1);
  close(taken);
  const std::string log = daemonStderr();
  const std::string expected =
      "binpickd: web view: cannot listen on 127.0.0.1:" + std::to_string(port) + ": Address already in use\n";
  EXPECT_NE(log.find(expected), std::string::npos) << log;
}

}  // namespace
}  // namespace binpick::cell::testing
