#pragma once
// Test support: a binpickd process on the virtual cell's bin, in its own temporary directory.
#include <gtest/gtest.h>

#include <fstream>
#include <memory>

#include "../cell/service/cell_scene.hpp"
#include "daemon_process.hpp"
#include "temp_directory_test.hpp"

namespace binpick::cell::testing {

class DaemonTest : public test::TempDirectoryTest {
 protected:
  // Writes the settings (the scene's, plus `extra`) and starts binpickd with a notify socket.
  void start(const std::string& extra = "", long watchdog_usec = 0) {
    config_path_ = pathOf("binpickd.yaml");
    writeConfig(extra);
    notify_ = std::make_unique<NotifySocket>(pathOf("notify"));
    DaemonOptions options;
    options.config_path = config_path_;
    options.port_file = pathOf("port");
    options.notify_socket = notify_->path();
    options.watchdog_usec = watchdog_usec;
    options.stderr_file = pathOf("stderr");
    daemon_ = std::make_unique<DaemonProcess>(options);
    port_ = daemon_->port();
  }
  void writeConfig(const std::string& extra) {
    std::ofstream(config_path_) << (config_text_.empty() ? cellConfigYaml(cellScene(), extra) : config_text_);
  }
  std::string daemonStderr() const {
    std::ifstream file(pathOf("stderr"));
    return std::string(std::istreambuf_iterator<char>(file), {});
  }

  std::string config_path_;
  std::string config_text_;  // set before start(): the settings written instead of the scene's
  std::unique_ptr<NotifySocket> notify_;
  std::unique_ptr<DaemonProcess> daemon_;
  int port_ = 0;
};

inline robot::Request request(robot::Command command, std::optional<std::string> argument = std::nullopt) {
  return robot::Request{command, std::move(argument)};
}

}  // namespace binpick::cell::testing
