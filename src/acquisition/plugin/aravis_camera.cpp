// AravisCamera: the Camera interface on one Aravis camera and its stream.
//
// Aravis objects are used from the caller's thread only; the one exception is the device's
// "control-lost" signal, which Aravis emits on its heartbeat thread and which only sets an atomic
// flag here. Aravis never reconnects by itself: after a lost connection, open() drops the old
// camera and stream and connects again from scratch.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <string>

#include "aravis_camera.hpp"
#include "aravis_configure.hpp"
#include "aravis_frame.hpp"
#include "aravis_support.hpp"
#include "binpick/core/component_logger.hpp"

namespace binpick::acquisition {
namespace {

using detail::GErrorSlot;
using detail::GObjectPtr;

// What the heartbeat thread may touch: shared, so that it outlives the camera object whatever
// order GLib releases things in.
struct LostSignal {
  std::shared_ptr<std::atomic<bool>> flag;
  std::string name;
};

void onControlLost(ArvDevice* /*device*/, gpointer data) {
  auto* signal = static_cast<LostSignal*>(data);
  signal->flag->store(true);
  core::componentLogger("camera")->error("{}: control lost (the camera stopped answering or another host took it)",
                                         signal->name);
}

void freeLostSignal(gpointer data, GClosure* /*closure*/) { delete static_cast<LostSignal*>(data); }

std::string readDescription(ArvCamera* camera) {
  auto text = [](const char* value) { return std::string(value != nullptr ? value : "?"); };
  return text(arv_camera_get_vendor_name(camera, nullptr)) + " " + text(arv_camera_get_model_name(camera, nullptr)) +
         " " + text(arv_camera_get_device_serial_number(camera, nullptr));
}

StreamStatistics readStatistics(ArvStream* stream) {
  StreamStatistics s;
  guint64 completed = 0, failures = 0, underruns = 0;
  arv_stream_get_statistics(stream, &completed, &failures, &underruns);
  s.completed_frames = completed;
  s.failed_frames = failures;
  s.underruns = underruns;
  if (ARV_IS_GV_STREAM(stream)) {
    guint64 resent = 0, missing = 0;
    arv_gv_stream_get_statistics(ARV_GV_STREAM(stream), &resent, &missing);
    s.resent_packets = resent;
    s.missing_packets = missing;
  }
  return s;
}

StreamStatistics since(const StreamStatistics& now, const StreamStatistics& base) {
  auto delta = [](uint64_t a, uint64_t b) { return a >= b ? a - b : 0; };
  StreamStatistics s;
  s.completed_frames = delta(now.completed_frames, base.completed_frames);
  s.failed_frames = delta(now.failed_frames, base.failed_frames);
  s.underruns = delta(now.underruns, base.underruns);
  s.missing_packets = delta(now.missing_packets, base.missing_packets);
  s.resent_packets = delta(now.resent_packets, base.resent_packets);
  return s;
}

Frame statusFrame(FrameStatus status, std::string detail) {
  Frame frame;
  frame.status = status;
  frame.detail = std::move(detail);
  return frame;
}

class AravisCamera final : public Camera {
 public:
  explicit AravisCamera(const CameraParams& params)
      : params_(params),
        layout_(detail::pixelLayout(params.pixel_format)),
        name_("camera '" + (params.id.empty() ? std::string("(first found)") : params.id) + "'") {}
  ~AravisCamera() override { close(); }
  AravisCamera(const AravisCamera&) = delete;
  AravisCamera& operator=(const AravisCamera&) = delete;

  void open() override;
  void close() override;
  bool isOpen() const override { return camera_ != nullptr; }
  void start() override;
  void stop() override;
  void trigger() override;
  Frame grab(int timeout_ms) override;
  bool connectionLost() const override { return lost_->load(); }
  StreamStatistics statistics() const override;
  std::string description() const override { return description_.empty() ? name_ : description_; }

 private:
  void connect();
  void createStream();
  void drainStream();
  void requireOpen(const char* operation) const;
  void stopStreaming();

  const CameraParams params_;
  const detail::PixelLayout layout_;
  const std::string name_;
  std::shared_ptr<std::atomic<bool>> lost_ = std::make_shared<std::atomic<bool>>(false);
  GObjectPtr<ArvCamera> camera_;
  GObjectPtr<ArvStream> stream_;
  gulong lost_handler_ = 0;
  bool streaming_ = false;
  std::string description_;
  StreamStatistics baseline_;  // the stream's counters at start()
  StreamStatistics last_run_;  // what statistics() says once the stream is gone
};

// A camera that was lost stays "lost" until a new connection stands: a failed open() leaves the
// flag as it was.
void AravisCamera::open() {
  close();
  last_run_ = StreamStatistics{};
  try {
    connect();
    lost_->store(false);
    detail::configureCamera(camera_.get(), params_, name_);
    createStream();
  } catch (...) {
    close();
    throw;
  }
  core::componentLogger("camera")->info("{}: opened {} ({}, {} buffers)", name_, description_, params_.pixel_format,
                                        params_.buffers);
}

void AravisCamera::connect() {
  GErrorSlot error;
  ArvCamera* camera = arv_camera_new(params_.id.empty() ? nullptr : params_.id.c_str(), error.out());
  if (camera == nullptr && !error.isSet()) throw core::Error(name_ + ": cannot open: no such camera");
  error.throwIfSet(name_ + ": cannot open");
  camera_.reset(camera);
  description_ = readDescription(camera);
  auto* signal = new LostSignal{lost_, name_};
  lost_handler_ = g_signal_connect_data(arv_camera_get_device(camera), "control-lost", G_CALLBACK(onControlLost),
                                        signal, freeLostSignal, GConnectFlags(0));
}

// Buffers are allocated once here and cycle between Aravis and grab() until close().
void AravisCamera::createStream() {
  GErrorSlot error;
  ArvStream* stream = arv_camera_create_stream(camera_.get(), nullptr, nullptr, error.out());
  if (stream == nullptr && !error.isSet()) throw core::Error(name_ + ": cannot create the stream");
  error.throwIfSet(name_ + ": cannot create the stream");
  stream_.reset(stream);
  const guint payload = arv_camera_get_payload(camera_.get(), error.out());
  error.throwIfSet(name_ + ": cannot read the payload size");
  for (int i = 0; i < params_.buffers; ++i) arv_stream_push_buffer(stream, arv_buffer_new_allocate(payload));
}

// On a camera that no longer answers this takes about 5 s: Aravis's stream finalizer still
// writes two stream-channel registers and waits out each write's retries (Aravis 0.8.26).
void AravisCamera::close() {
  if (camera_ == nullptr) return;
  stopStreaming();
  // The stream first: its thread uses the device. Unreffing the device joins its heartbeat
  // thread, so no control-lost handler runs after this.
  stream_.reset();
  if (lost_handler_ != 0) g_signal_handler_disconnect(arv_camera_get_device(camera_.get()), lost_handler_);
  lost_handler_ = 0;
  camera_.reset();
}

void AravisCamera::requireOpen(const char* operation) const {
  if (camera_ == nullptr) throw core::Error(name_ + ": " + operation + "() before open()");
}

void AravisCamera::start() {
  requireOpen("start");
  if (streaming_) return;
  drainStream();
  baseline_ = readStatistics(stream_.get());
  GErrorSlot error;
  arv_camera_start_acquisition(camera_.get(), error.out());
  error.throwIfSet(name_ + ": cannot start acquisition");
  streaming_ = true;
}

// Frames completed before stop() would otherwise come out of the next run's first grab().
void AravisCamera::drainStream() {
  while (ArvBuffer* buffer = arv_stream_try_pop_buffer(stream_.get())) arv_stream_push_buffer(stream_.get(), buffer);
}

void AravisCamera::stop() {
  if (!streaming_) return;
  streaming_ = false;
  last_run_ = since(readStatistics(stream_.get()), baseline_);
  const StreamStatistics& s = last_run_;
  core::componentLogger("camera")->info(
      "{}: stopped: {} frames completed, {} failed, {} underruns, {} packets missing, {} resent", name_,
      s.completed_frames, s.failed_frames, s.underruns, s.missing_packets, s.resent_packets);
  // A camera that is gone cannot be told to stop: asking only waits out the GVCP retries.
  if (lost_->load()) return;
  GErrorSlot error;
  arv_camera_stop_acquisition(camera_.get(), error.out());
  error.throwIfSet(name_ + ": cannot stop acquisition");
}

void AravisCamera::stopStreaming() {
  try {
    stop();
  } catch (const core::Error& e) {
    core::componentLogger("camera")->warn("{}", e.what());
  }
}

// After a lost connection the trigger is skipped, not sent: the write would only time out after
// Aravis's retries, and grab() reports the lost connection at once.
void AravisCamera::trigger() {
  if (params_.trigger != TriggerSource::Software) return;
  requireOpen("trigger");
  if (lost_->load()) return;
  GErrorSlot error;
  arv_camera_software_trigger(camera_.get(), error.out());
  error.throwIfSet(name_ + ": software trigger failed");
}

// Waits in short slices so that a connection lost mid-wait is reported without sitting out the
// whole timeout. The buffer goes back to the stream whatever its status.
Frame AravisCamera::grab(int timeout_ms) {
  using Clock = std::chrono::steady_clock;
  if (camera_ == nullptr || !streaming_) return statusFrame(FrameStatus::Failed, name_ + " is not streaming");
  constexpr auto kSlice = std::chrono::milliseconds(50);
  const auto deadline = Clock::now() + std::chrono::milliseconds(std::max(timeout_ms, 0));
  for (;;) {
    if (lost_->load()) return statusFrame(FrameStatus::ConnectionLost, name_ + ": control lost");
    const auto left = std::chrono::duration_cast<std::chrono::microseconds>(deadline - Clock::now());
    const auto wait = std::clamp(left, std::chrono::microseconds(0), std::chrono::microseconds(kSlice));
    if (ArvBuffer* buffer = arv_stream_timeout_pop_buffer(stream_.get(), static_cast<guint64>(wait.count()))) {
      Frame frame = detail::frameFromBuffer(buffer, layout_);
      arv_stream_push_buffer(stream_.get(), buffer);
      return frame;
    }
    if (Clock::now() >= deadline) {
      return statusFrame(FrameStatus::Timeout, "no frame within " + std::to_string(timeout_ms) + " ms");
    }
  }
}

StreamStatistics AravisCamera::statistics() const {
  if (stream_ == nullptr || !streaming_) return last_run_;
  return since(readStatistics(stream_.get()), baseline_);
}

}  // namespace

Camera* detail::newAravisCamera(const CameraParams& params) { return new AravisCamera(params); }

}  // namespace binpick::acquisition
