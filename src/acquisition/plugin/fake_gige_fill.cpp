// The fake GigE camera's frames: a copy of the served image, cut to the client's region.
#include "fake_gige_fill.hpp"

#include "binpick/core/error.hpp"

namespace binpick::acquisition::detail {

void ServedImage::configure(int width, int height, bool sixteen_bit) {
  const std::lock_guard<std::mutex> lock(mutex_);
  size_ = cv::Size(width, height);
  type_ = sixteen_bit ? CV_16UC1 : CV_8UC1;
  image_.release();
}

void ServedImage::set(const cv::Mat& image) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (image.size() != size_ || image.type() != type_) {
    throw core::Error("fake camera: served image must be " + std::to_string(size_.width) + "x" +
                      std::to_string(size_.height) + (type_ == CV_8UC1 ? " 8-bit" : " 16-bit") + " grey (got " +
                      std::to_string(image.cols) + "x" + std::to_string(image.rows) + ", OpenCV type " +
                      std::to_string(image.type()) + ")");
  }
  image.copyTo(image_);
}

// The client may pick another region or depth than the fake's defaults; it gets the matching
// window of the served image, converted the way a sensor would fill the other depth (16-bit
// values keep the 8-bit value in their high byte).
void ServedImage::copyTo(uint8_t* pixels, const cv::Rect& region, ArvPixelFormat format) const {
  const int type = format == ARV_PIXEL_FORMAT_MONO_16 ? CV_16UC1 : CV_8UC1;
  cv::Mat out(region.height, region.width, type, pixels);
  out.setTo(0);
  const std::lock_guard<std::mutex> lock(mutex_);
  if (image_.empty()) return;
  const cv::Rect inside = region & cv::Rect(0, 0, image_.cols, image_.rows);
  if (inside.empty()) return;
  cv::Mat target = out(inside - region.tl());
  const cv::Mat source = image_(inside);
  if (source.type() == type) {
    source.copyTo(target);
  } else {
    source.convertTo(target, type, type == CV_16UC1 ? 256.0 : 1.0 / 256.0);
  }
}

void fillFromServedImage(ArvBuffer* buffer, void* data, guint32 /*exposure_time_us*/, guint32 /*gain*/,
                         ArvPixelFormat format) {
  // Inside the callback Aravis reports the data size as 0: the frame's size comes from its
  // region, which the fake has checked against the buffer's allocation before calling us.
  size_t unused = 0;
  auto* pixels = static_cast<uint8_t*>(const_cast<void*>(arv_buffer_get_data(buffer, &unused)));
  const cv::Rect region(arv_buffer_get_image_x(buffer), arv_buffer_get_image_y(buffer),
                        arv_buffer_get_image_width(buffer), arv_buffer_get_image_height(buffer));
  if (pixels == nullptr || region.width <= 0 || region.height <= 0) return;
  static_cast<const ServedImage*>(data)->copyTo(pixels, region, format);
}

}  // namespace binpick::acquisition::detail
