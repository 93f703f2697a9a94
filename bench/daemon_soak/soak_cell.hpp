#pragma once
// The soak's cell: binpickd settings for the virtual cell's test bin (replayed, rendered once per
// build tree), with a calibration file of its own that reloads break and restore, and binpickd
// running on them with its log in a file.
#include <memory>
#include <string>

#include "daemon_process.hpp"
#include "notify_listener.hpp"

namespace binpick::bench::soak {

// What a reload puts on disk before its SIGHUP. Every kind but Valid leaves the cell without a
// usable rig calibration, which binpickd must refuse, keeping the running settings.
enum class ReloadKind { Valid, Garbage, Truncated, Removed };
const char* reloadKindName(ReloadKind kind);
inline bool isBroken(ReloadKind kind) { return kind != ReloadKind::Valid; }

class SoakCell {
 public:
  // Writes the settings into `directory` (created): the test bin's, with every thread count at
  // `threads`, the model caches and the calibration in the directory.
  SoakCell(const std::string& directory, int threads);
  // Starts binpickd and waits until it serves (READY=1); throws when it does not. From then on its
  // service manager messages are read as they come (notifications()).
  void start();
  // The settings again, and the calibration as `kind` says; binpickd reads both at its next SIGHUP.
  void prepareReload(ReloadKind kind);

  cell::testing::DaemonProcess& daemon() { return *daemon_; }
  NotifyListener& notifications() { return *notifications_; }
  int port() const { return port_; }
  std::string logPath() const { return directory_ + "/binpickd.log"; }
  const std::string& directory() const { return directory_; }
  static std::string sceneDirectory();  // the test bin's capture, model and calibration

 private:
  std::string directory_;
  std::string settings_path_;
  std::string settings_;
  std::string calibration_path_;
  std::string calibration_;  // the good file's bytes, to restore
  std::unique_ptr<cell::testing::NotifySocket> notify_;
  std::unique_ptr<NotifyListener> notifications_;  // after the socket it reads: gone before it
  std::unique_ptr<cell::testing::DaemonProcess> daemon_;
  int port_ = 0;
};

}  // namespace binpick::bench::soak
