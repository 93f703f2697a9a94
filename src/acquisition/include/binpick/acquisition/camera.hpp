#pragma once
// A machine-vision camera as the capture sequencer uses it: configure, start streaming, trigger,
// take the next frame or learn why there is none. The Aravis (GigE Vision / USB3 Vision)
// implementation is aravis_camera.hpp; tests use a fake behind the same interface.
//
// Thread-safety: a Camera is used from one thread (Aravis objects are not thread-safe), except
// connectionLost(), which may be read from any thread.
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <string>

namespace binpick::acquisition {

enum class TriggerSource {
  Software,  // the sequencer triggers each frame (trigger())
  Hardware,  // an input line (e.g. the projector's sync output) triggers each frame
  FreeRun,   // the camera streams continuously; frames are taken as they come
};

struct CameraParams {
  std::string id;                      // device id, serial number or IP address; "" = first found
  std::string pixel_format = "Mono8";  // Mono8, or Mono10/Mono12/Mono16 (delivered as 16-bit, high bits)
  double exposure_us = 8000.0;
  double gain_db = 0.0;
  cv::Rect roi;         // sensor region; empty = the whole sensor
  int packet_size = 0;  // GigE Vision packet size, bytes; 0 = negotiate
  TriggerSource trigger = TriggerSource::Software;
  std::string hardware_trigger_line = "Line1";  // for TriggerSource::Hardware
  int buffers = 8;                              // stream buffers, allocated once and reused
  void validate() const;                        // throws core::Error naming the field
};

enum class FrameStatus {
  Ok,
  Timeout,         // no frame within the timeout
  Incomplete,      // the frame arrived with missing or bad packets: its pixels are not trusted
  ConnectionLost,  // the camera stopped answering (unplugged, power, network)
  Failed,          // any other stream error
};
const char* frameStatusName(FrameStatus status);

struct Frame {
  FrameStatus status = FrameStatus::Failed;
  cv::Mat image;                // CV_8UC1 or CV_16UC1, owns its pixels; empty unless Ok
  uint64_t frame_id = 0;        // the camera's frame counter
  uint64_t timestamp_ns = 0;    // the camera's time stamp (0 when it gives none)
  uint64_t system_time_ns = 0;  // host time the frame was received (CLOCK_REALTIME)
  std::string detail;           // what went wrong, for logs and errors
};

// Stream counters since start(): what a cell operator looks at when frames go missing.
struct StreamStatistics {
  uint64_t completed_frames = 0;
  uint64_t failed_frames = 0;
  uint64_t underruns = 0;  // frames lost for want of a free buffer
  uint64_t missing_packets = 0;
  uint64_t resent_packets = 0;
};

class Camera {
 public:
  virtual ~Camera() = default;
  // Connects and applies the params. Throws core::Error naming the camera on failure.
  virtual void open() = 0;
  virtual void close() = 0;
  virtual bool isOpen() const = 0;
  // Streams frames into the reused buffers; stop() ends it. Throws core::Error on failure.
  virtual void start() = 0;
  virtual void stop() = 0;
  // Software trigger (a no-op for hardware and free-running triggers).
  virtual void trigger() = 0;
  // The next frame, or why there is none within `timeout_ms`. Never throws for stream faults:
  // they are statuses.
  virtual Frame grab(int timeout_ms) = 0;
  // True once the camera stopped answering (set from the camera's heartbeat thread); open()
  // clears it.
  virtual bool connectionLost() const = 0;
  virtual StreamStatistics statistics() const = 0;
  // Vendor, model and serial number, for logs and capture metadata.
  virtual std::string description() const = 0;
};

}  // namespace binpick::acquisition
