// The image-codecs plugin: OpenCV's imgcodecs behind the table of image_codecs_abi.hpp. It is the
// one part of binpick that links them (binpick/io/image_file.hpp says why). OpenCV reports most
// failures by an empty result and some by cv::Exception (a corrupt stream, an unsupported depth);
// both become the empty result here, as no exception should cross the plugin's boundary.
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "image_codecs_abi.hpp"

namespace {

cv::Mat read(const std::string& path, int flags) {
  try {
    return cv::imread(path, flags);
  } catch (const cv::Exception&) {
    return {};
  }
}

cv::Mat decode(const std::string& bytes, int flags) {
  if (bytes.empty()) return {};
  // A view of the bytes, not a copy: imdecode only reads them.
  const cv::Mat buffer(1, static_cast<int>(bytes.size()), CV_8UC1, const_cast<char*>(bytes.data()));
  try {
    return cv::imdecode(buffer, flags);
  } catch (const cv::Exception&) {
    return {};
  }
}

bool write(const std::string& path, const cv::Mat& image, std::string& why) {
  try {
    return cv::imwrite(path, image);
  } catch (const cv::Exception& error) {
    // OpenCV refuses some images (2 channels, 32-bit float in PNG) by assertion.
    why = error.err;
    return false;
  }
}

std::string encodePng(const cv::Mat& image, int compression_level) {
  std::vector<uchar> bytes;
  const std::vector<int> options{cv::IMWRITE_PNG_COMPRESSION, compression_level};
  try {
    if (!cv::imencode(".png", image, bytes, options)) return {};
  } catch (const cv::Exception&) {
    return {};
  }
  return std::string(bytes.begin(), bytes.end());
}

const binpick::io::detail::ImageCodecs kCodecs{binpick::io::detail::kImageCodecsVersion, read, decode, write,
                                               encodePng};

}  // namespace

extern "C" const binpick::io::detail::ImageCodecs* binpick_image_codecs() { return &kCodecs; }
