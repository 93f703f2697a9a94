// The replay source: recorded capture directories, in name order, read as they were written.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "binpick/acquisition/capture_source.hpp"
#include "binpick/core/component_logger.hpp"
#include "binpick/core/error.hpp"

namespace binpick::acquisition {
namespace {

namespace fs = std::filesystem;

bool isCapture(const fs::path& directory) {
  std::error_code error;
  return fs::is_regular_file(directory / "capture.json", error);
}

// PATH (a directory) itself when it is a capture, else its subdirectories in name order. A subdirectory without
// capture.json is refused rather than skipped: writeCapture writes capture.json last, so it is a
// recording that never finished (or something else that does not belong there) and a silently
// shorter replay would hide that.
std::vector<std::string> listCaptures(const std::string& path) {
  if (isCapture(path)) return {path};
  std::vector<fs::path> directories;
  std::error_code error;
  for (fs::directory_iterator it(path, error), end; !error && it != end; it.increment(error)) {
    std::error_code type_error;
    if (it->is_directory(type_error)) directories.push_back(it->path());  // files (notes, calib) ignored
  }
  if (error) throw core::Error("replay: cannot list " + path + ": " + error.message());
  std::sort(directories.begin(), directories.end());
  std::vector<std::string> captures;
  for (const fs::path& directory : directories) {
    if (!isCapture(directory)) {
      throw core::Error(
          "replay: " + directory.string() +
          " has no capture.json (a recording that did not finish?); remove it or replay another directory");
    }
    captures.push_back(directory.string());
  }
  return captures;
}

// A path that holds no capture yet (missing, or empty) is the normal state of a cell set up but
// not yet recorded: the source starts, every next() says why it has nothing, and the captures are
// looked for again then, so that a recording copied in later is replayed without a restart. A
// half-written recording is still refused at once: it needs a person.
class ReplaySource : public CaptureSource {
 public:
  explicit ReplaySource(const ReplayParams& params) : params_(params) {
    if (!findCaptures(params_.path)) {
      core::componentLogger("replay")->warn("{}; every capture fails until there is one", missing_);
      return;
    }
    core::componentLogger("replay")->info("{}: {} capture(s){}", params_.path, captures_.size(),
                                          params_.loop ? ", looping" : "");
  }

  std::string description() const override {
    if (captures_.empty()) return "replay of " + params_.path + " (no capture yet)";
    return "replay of " + params_.path + " (" + std::to_string(captures_.size()) + " capture(s))";
  }

 private:
  io::Capture nextCapture(const core::CancelFlag* cancel) override {
    core::throwIfCancelled(cancel, "before reading the recording");
    if (captures_.empty() && !findCaptures(params_.path)) throw core::Error("replay: " + missing_);
    if (next_ == captures_.size()) {
      if (!params_.loop) throw core::Error("replay: no more captures in " + params_.path);
      next_ = 0;
    }
    // Move on before reading: a damaged capture is reported once and the replay goes on after it.
    const std::string& directory = captures_[next_++];
    core::componentLogger("replay")->debug("reading {}", directory);
    return io::readCapture(directory, params_.threads);
  }

  // Lists the captures; false (with missing_ saying why) when the path holds none yet.
  bool findCaptures(const std::string& path) {
    std::error_code error;
    if (!fs::is_directory(path, error)) {
      missing_ = path + " is not a directory";
      return false;
    }
    captures_ = listCaptures(path);
    if (captures_.empty()) {
      missing_ = path + " holds no capture (no capture.json in it or its subdirectories)";
      return false;
    }
    return true;
  }

  ReplayParams params_;
  std::vector<std::string> captures_;
  std::string missing_;  // why there is no capture, while there is none
  std::size_t next_ = 0;
};

}  // namespace

std::unique_ptr<CaptureSource> makeReplaySource(const ReplayParams& params) {
  const std::string owner = "replay params";
  core::requireField(!params.path.empty(), owner, "path", "a capture directory or a directory of them", "\"\"");
  core::requireField(params.threads >= 0, owner, "threads", ">= 0 (0: all cores)", params.threads);
  return std::make_unique<ReplaySource>(params);
}

}  // namespace binpick::acquisition
