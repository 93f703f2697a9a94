#pragma once
// Internal: the image a FakeGigECamera serves, and the fill-pattern callback through which
// Aravis's fake camera thread copies it into each frame.
#include <arv.h>

#include <mutex>
#include <opencv2/core.hpp>

namespace binpick::acquisition::detail {

class ServedImage {
 public:
  void configure(int width, int height, bool sixteen_bit);
  // Throws core::Error unless `image` has the camera's size and depth. Copies it.
  void set(const cv::Mat& image);
  // Writes the `region` of the served image (the client's ROI) into `pixels` as `format` (Mono8
  // or Mono16); parts outside the image, or everything before the first set(), are black.
  void copyTo(uint8_t* pixels, const cv::Rect& region, ArvPixelFormat format) const;

 private:
  mutable std::mutex mutex_;
  cv::Mat image_;
  cv::Size size_;
  int type_ = CV_8UC1;
};

// ArvFakeCameraFillPattern with `data` = the ServedImage. Runs on Aravis's fake camera thread.
void fillFromServedImage(ArvBuffer* buffer, void* data, guint32 exposure_time_us, guint32 gain, ArvPixelFormat format);

}  // namespace binpick::acquisition::detail
