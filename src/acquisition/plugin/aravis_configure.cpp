// configureCamera: CameraParams -> GenICam features through ArvCamera's helpers.
#include "aravis_configure.hpp"

#include <sstream>

#include "aravis_support.hpp"

namespace binpick::acquisition::detail {
namespace {

template <typename T>
std::string cannotSet(const std::string& name, const char* field, const T& value) {
  std::ostringstream text;
  text << name << ": cannot set " << field << " to " << value;
  return text.str();
}

void setPixelFormat(ArvCamera* camera, const CameraParams& params, const std::string& name) {
  GErrorSlot error;
  arv_camera_set_pixel_format_from_string(camera, params.pixel_format.c_str(), error.out());
  error.throwIfSet(cannotSet(name, "pixel_format", params.pixel_format));
}

std::string regionText(const cv::Rect& r) {
  std::ostringstream text;
  text << r.width << "x" << r.height << "+" << r.x << "+" << r.y;
  return text.str();
}

// The largest region at offset 0 (offsets first: on many cameras the widest width shrinks with
// the x offset).
cv::Rect fullSensor(ArvCamera* camera, const std::string& name) {
  GErrorSlot error;
  arv_camera_set_region(camera, 0, 0, 0, 0, error.out());  // sizes <= 0 are left alone
  int min_width = 0, max_width = 0, min_height = 0, max_height = 0;
  if (!error.isSet()) arv_camera_get_width_bounds(camera, &min_width, &max_width, error.out());
  if (!error.isSet()) arv_camera_get_height_bounds(camera, &min_height, &max_height, error.out());
  error.throwIfSet(name + ": cannot read the sensor size");
  return cv::Rect(0, 0, max_width, max_height);
}

// An empty ROI means the whole sensor, not whatever region the last program left. A region is
// checked against the sensor and read back: cameras may silently clamp or round it.
void setRegion(ArvCamera* camera, const CameraParams& params, const std::string& name) {
  const cv::Rect sensor = fullSensor(camera, name);
  const cv::Rect roi = params.roi.empty() ? sensor : params.roi;
  if ((roi & sensor) != roi) {
    throw core::Error(cannotSet(name, "roi", regionText(roi)) + ": outside the " + std::to_string(sensor.width) + "x" +
                      std::to_string(sensor.height) + " sensor");
  }
  GErrorSlot error;
  arv_camera_set_region(camera, roi.x, roi.y, roi.width, roi.height, error.out());
  error.throwIfSet(cannotSet(name, "roi", regionText(roi)));
  cv::Rect actual;
  arv_camera_get_region(camera, &actual.x, &actual.y, &actual.width, &actual.height, error.out());
  error.throwIfSet(name + ": cannot read the region back");
  if (actual != roi)
    throw core::Error(cannotSet(name, "roi", regionText(roi)) + ": the camera made it " + regionText(actual));
}

// Aravis 0.8 writes a value outside the feature's bounds without complaint (the fake camera
// takes it), so the bounds are checked here.
void requireWithin(double value, double min, double max, const std::string& refusal) {
  if (value >= min && value <= max) return;
  std::ostringstream text;
  text << refusal << ": outside the camera's [" << min << ", " << max << "]";
  throw core::Error(text.str());
}

// Automatic exposure and gain would change the images between the patterns of one capture.
void setExposure(ArvCamera* camera, const CameraParams& params, const std::string& name) {
  GErrorSlot error;
  if (arv_camera_is_exposure_auto_available(camera, nullptr)) {
    arv_camera_set_exposure_time_auto(camera, ARV_AUTO_OFF, error.out());
    error.throwIfSet(cannotSet(name, "exposure auto", "Off"));
  }
  double min = 0.0, max = 0.0;
  arv_camera_get_exposure_time_bounds(camera, &min, &max, error.out());
  error.throwIfSet(name + ": cannot read the exposure bounds");
  requireWithin(params.exposure_us, min, max, cannotSet(name, "exposure_us", params.exposure_us));
  arv_camera_set_exposure_time(camera, params.exposure_us, error.out());
  error.throwIfSet(cannotSet(name, "exposure_us", params.exposure_us));
}

void setGain(ArvCamera* camera, const CameraParams& params, const std::string& name) {
  GErrorSlot error;
  if (!arv_camera_is_gain_available(camera, nullptr)) {
    if (params.gain_db != 0.0)
      throw core::Error(cannotSet(name, "gain_db", params.gain_db) + ": the camera has no gain");
    return;
  }
  if (arv_camera_is_gain_auto_available(camera, nullptr)) {
    arv_camera_set_gain_auto(camera, ARV_AUTO_OFF, error.out());
    error.throwIfSet(cannotSet(name, "gain auto", "Off"));
  }
  double min = 0.0, max = 0.0;
  arv_camera_get_gain_bounds(camera, &min, &max, error.out());
  error.throwIfSet(name + ": cannot read the gain bounds");
  requireWithin(params.gain_db, min, max, cannotSet(name, "gain_db", params.gain_db));
  arv_camera_set_gain(camera, params.gain_db, error.out());
  error.throwIfSet(cannotSet(name, "gain_db", params.gain_db));
}

void setTrigger(ArvCamera* camera, const CameraParams& params, const std::string& name) {
  GErrorSlot error;
  arv_camera_set_acquisition_mode(camera, ARV_ACQUISITION_MODE_CONTINUOUS, error.out());
  error.throwIfSet(cannotSet(name, "acquisition mode", "Continuous"));
  switch (params.trigger) {
    case TriggerSource::Software:
      arv_camera_set_trigger(camera, "Software", error.out());
      error.throwIfSet(cannotSet(name, "trigger", "Software"));
      break;
    case TriggerSource::Hardware:
      arv_camera_set_trigger(camera, params.hardware_trigger_line.c_str(), error.out());
      error.throwIfSet(cannotSet(name, "hardware_trigger_line", params.hardware_trigger_line));
      break;
    case TriggerSource::FreeRun:
      arv_camera_clear_triggers(camera, error.out());
      error.throwIfSet(cannotSet(name, "trigger", "free run"));
      break;
  }
}

// Only GigE Vision has packets. 0 asks Aravis for the largest size that reaches this host (on
// cameras without a test packet it keeps the camera's current size).
void setPacketSize(ArvCamera* camera, const CameraParams& params, const std::string& name) {
  if (!arv_camera_is_gv_device(camera)) return;
  GErrorSlot error;
  if (params.packet_size > 0) {
    arv_camera_gv_set_packet_size(camera, params.packet_size, error.out());
    error.throwIfSet(cannotSet(name, "packet_size", params.packet_size));
  } else {
    arv_camera_gv_auto_packet_size(camera, error.out());
    error.throwIfSet(name + ": cannot negotiate the packet size");
  }
}

}  // namespace

void configureCamera(ArvCamera* camera, const CameraParams& params, const std::string& name) {
  setPixelFormat(camera, params, name);
  setRegion(camera, params, name);
  setExposure(camera, params, name);
  setGain(camera, params, name);
  setTrigger(camera, params, name);
  setPacketSize(camera, params, name);
}

}  // namespace binpick::acquisition::detail
