// Aravis buffer -> Frame: status mapping and the pixel copy.
#include "aravis_frame.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "binpick/core/error.hpp"

// GenICam's Mono10/12/16 are little-endian 16-bit words: copied as they are, they are only right
// on a little-endian host.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "16-bit camera pixels are copied as little-endian");

namespace binpick::acquisition::detail {
namespace {

uint64_t realtimeNowNs() {
  const auto now = std::chrono::system_clock::now().time_since_epoch();
  return static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(now).count());
}

std::string hex(ArvPixelFormat format) {
  char text[16];
  std::snprintf(text, sizeof(text), "0x%08x", static_cast<unsigned>(format));
  return text;
}

Frame failed(Frame frame, const std::string& detail) {
  frame.status = FrameStatus::Failed;
  frame.detail = detail;
  frame.image.release();
  return frame;
}

// Row by row: the camera may pad its lines, and Mono10/12 move up to the high bits on the way.
void copyRows(const uint8_t* source, size_t source_stride, const PixelLayout& layout, cv::Mat& image) {
  const size_t row_bytes = static_cast<size_t>(image.cols) * static_cast<size_t>(layout.bytes_per_pixel);
  for (int y = 0; y < image.rows; ++y) {
    const uint8_t* row = source + static_cast<size_t>(y) * source_stride;
    if (layout.shift == 0) {
      std::memcpy(image.ptr(y), row, row_bytes);
      continue;
    }
    uint16_t* out = image.ptr<uint16_t>(y);
    for (int x = 0; x < image.cols; ++x) {
      uint16_t value;
      std::memcpy(&value, row + 2 * static_cast<size_t>(x), sizeof(value));  // may be unaligned
      out[x] = static_cast<uint16_t>(value << layout.shift);
    }
  }
}

}  // namespace

PixelLayout pixelLayout(const std::string& pixel_format) {
  if (pixel_format == "Mono8") return {ARV_PIXEL_FORMAT_MONO_8, 1, 0};
  if (pixel_format == "Mono10") return {ARV_PIXEL_FORMAT_MONO_10, 2, 6};
  if (pixel_format == "Mono12") return {ARV_PIXEL_FORMAT_MONO_12, 2, 4};
  if (pixel_format == "Mono16") return {ARV_PIXEL_FORMAT_MONO_16, 2, 0};
  throw core::Error("camera pixel format '" + pixel_format + "' is not one of Mono8, Mono10, Mono12, Mono16");
}

FrameStatus frameStatus(ArvBufferStatus status) {
  switch (status) {
    case ARV_BUFFER_STATUS_SUCCESS: return FrameStatus::Ok;
    // Aravis's buffer TIMEOUT means the frame started arriving but its missing packets never
    // came (frame retention expired): an incomplete frame, not "no frame" (that is a pop
    // timeout, which grab reports as Timeout).
    case ARV_BUFFER_STATUS_TIMEOUT:
    case ARV_BUFFER_STATUS_MISSING_PACKETS:
    case ARV_BUFFER_STATUS_WRONG_PACKET_ID:
    case ARV_BUFFER_STATUS_SIZE_MISMATCH: return FrameStatus::Incomplete;
    default: return FrameStatus::Failed;
  }
}

const char* bufferStatusName(ArvBufferStatus status) {
  switch (status) {
    case ARV_BUFFER_STATUS_UNKNOWN: return "unknown buffer status";
    case ARV_BUFFER_STATUS_SUCCESS: return "success";
    case ARV_BUFFER_STATUS_CLEARED: return "buffer cleared";
    case ARV_BUFFER_STATUS_TIMEOUT: return "packets missing when the frame timed out";
    case ARV_BUFFER_STATUS_MISSING_PACKETS: return "missing packets";
    case ARV_BUFFER_STATUS_WRONG_PACKET_ID: return "wrong packet id";
    case ARV_BUFFER_STATUS_SIZE_MISMATCH: return "frame larger than the buffer";
    case ARV_BUFFER_STATUS_FILLING: return "buffer still filling";
    case ARV_BUFFER_STATUS_ABORTED: return "acquisition aborted";
  }
  return "unexpected buffer status";
}

Frame frameFromBuffer(ArvBuffer* buffer, const PixelLayout& layout) {
  Frame frame;
  const ArvBufferStatus status = arv_buffer_get_status(buffer);
  frame.status = frameStatus(status);
  frame.frame_id = arv_buffer_get_frame_id(buffer);
  frame.timestamp_ns = arv_buffer_get_timestamp(buffer);
  frame.system_time_ns = arv_buffer_get_system_timestamp(buffer);
  if (frame.system_time_ns == 0) frame.system_time_ns = realtimeNowNs();
  if (frame.status != FrameStatus::Ok) {
    frame.detail = std::string("frame ") + std::to_string(frame.frame_id) + ": " + bufferStatusName(status);
    return frame;
  }

  if (arv_buffer_get_image_pixel_format(buffer) != layout.format) {
    return failed(std::move(frame), "frame pixel format " + hex(arv_buffer_get_image_pixel_format(buffer)) +
                                        " is not the configured " + hex(layout.format));
  }
  const int width = arv_buffer_get_image_width(buffer);
  const int height = arv_buffer_get_image_height(buffer);
  int x_padding = 0;
  int y_padding = 0;
  arv_buffer_get_image_padding(buffer, &x_padding, &y_padding);
  size_t size = 0;
  const auto* data = static_cast<const uint8_t*>(arv_buffer_get_image_data(buffer, &size));
  const size_t stride =
      static_cast<size_t>(width) * layout.bytes_per_pixel + static_cast<size_t>(std::max(x_padding, 0));
  const size_t needed =
      height > 0 ? stride * static_cast<size_t>(height - 1) + static_cast<size_t>(width) * layout.bytes_per_pixel : 0;
  if (data == nullptr || width <= 0 || height <= 0 || size < needed) {
    return failed(std::move(frame), "frame holds no " + std::to_string(width) + "x" + std::to_string(height) +
                                        " image (" + std::to_string(size) + " bytes)");
  }
  frame.image.create(height, width, layout.bytes_per_pixel == 1 ? CV_8UC1 : CV_16UC1);
  copyRows(data, stride, layout, frame.image);
  return frame;
}

}  // namespace binpick::acquisition::detail
