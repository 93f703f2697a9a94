// The `source:` section: replay directory or live camera + projector.
#include <filesystem>

#include "config_sections.hpp"

namespace binpick::cell {
namespace {

acquisition::CameraParams readCamera(core::YamlSection s) {
  acquisition::CameraParams camera;
  s.read("id", camera.id);
  s.read("pixel_format", camera.pixel_format);
  s.read("exposure_us", camera.exposure_us);
  s.read("gain_db", camera.gain_db);
  s.read("packet_size", camera.packet_size);
  s.finish();
  return camera;
}

io::PatternSetSpec readPatterns(core::YamlSection s) {
  io::PatternSetSpec spec;
  s.read("projector_width", spec.projector_width);
  s.read("projector_height", spec.projector_height);
  s.read("row_codes", spec.row_codes);
  s.read("phase_steps", spec.phase_steps);
  s.read("phase_period", spec.phase_period);
  s.read("gray_unit", spec.gray_unit);
  s.finish();
  return spec;
}

void readSequencer(core::YamlSection s, acquisition::LiveParams& live) {
  s.read("settle_us", live.sequencer.settle_us);
  s.read("frame_timeout_ms", live.sequencer.frame_timeout_ms);
  s.read("max_retries", live.sequencer.max_retries);
  s.read("reopen_backoff_ms", live.reopen_backoff_ms);
  s.read("max_reopen_backoff_ms", live.max_reopen_backoff_ms);
  s.finish();
}

LiveSourceConfig readLive(core::YamlSection s) {
  LiveSourceConfig live;
  live.camera = readCamera(s.child("camera"));
  live.live.patterns = readPatterns(s.child("patterns"));
  readSequencer(s.child("sequencer"), live.live);
  s.read("trigger", live.trigger);
  core::YamlSection gpio = s.child("gpio");
  gpio.read("chip", live.gpio.chip);
  gpio.read("line", live.gpio.line);
  gpio.read("active_high", live.gpio.active_high);
  gpio.read("pulse_us", live.gpio.pulse_us);
  gpio.finish();
  s.finish();
  if (live.trigger != "none" && live.trigger != "gpio") s.fail("trigger", "must be none or gpio");
  return live;
}

}  // namespace

std::string PathResolver::operator()(const std::string& path) const {
  if (path.empty()) return path;
  const std::filesystem::path p(path);
  return p.is_absolute() ? path : (std::filesystem::path(base_directory) / p).lexically_normal().string();
}

SourceConfig readSource(core::YamlSection s, const PathResolver& resolve) {
  SourceConfig source;
  std::string mode = "replay";
  s.read("mode", mode);
  if (mode == "live") {
    source.mode = SourceConfig::Mode::Live;
  } else if (mode != "replay") {
    s.fail("mode", "must be replay or live (got " + mode + ")");
  }
  source.replay.loop = true;
  core::YamlSection replay = s.child("replay");
  replay.read("path", source.replay.path);
  replay.read("loop", source.replay.loop);
  replay.read("threads", source.replay.threads);
  replay.finish();
  source.replay.path = resolve(source.replay.path);
  source.live = readLive(s.child("live"));
  s.finish();
  if (source.mode == SourceConfig::Mode::Replay && source.replay.path.empty()) {
    s.fail("replay.path", "is needed in replay mode");
  }
  return source;
}

}  // namespace binpick::cell
