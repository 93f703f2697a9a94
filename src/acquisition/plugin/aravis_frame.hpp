#pragma once
// Internal: an Aravis stream buffer -> our Frame (status and an owned copy of the pixels).
#include <arv.h>

#include <string>

#include "binpick/acquisition/camera.hpp"

namespace binpick::acquisition::detail {

// The pixel layout a CameraParams::pixel_format asks for.
struct PixelLayout {
  ArvPixelFormat format = ARV_PIXEL_FORMAT_MONO_8;
  int bytes_per_pixel = 1;
  int shift = 0;  // left shift that puts the sensor's bits at the top of 16 (Mono12: 4)
};
// Throws core::Error for a format we do not take (CameraParams::validate lists them).
PixelLayout pixelLayout(const std::string& pixel_format);

// What Aravis's buffer status means for the sequencer.
FrameStatus frameStatus(ArvBufferStatus status);
const char* bufferStatusName(ArvBufferStatus status);

// The frame in `buffer`: for a successful buffer its pixels are copied into a fresh cv::Mat
// (8-bit, or 16-bit with the value shifted to the high bits); a buffer that does not hold the
// image `layout` describes is Failed with a detail saying why. Does not touch the buffer's queue.
Frame frameFromBuffer(ArvBuffer* buffer, const PixelLayout& layout);

}  // namespace binpick::acquisition::detail
