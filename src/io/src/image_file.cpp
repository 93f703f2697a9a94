// Image files through the image-codecs plugin (binpick/io/image_file.hpp says why a plugin).
#include "binpick/io/image_file.hpp"

#include <opencv2/imgcodecs.hpp>

#include "binpick/core/error.hpp"
#include "binpick/core/plugin.hpp"
#include "image_codecs_abi.hpp"

namespace binpick::io {
namespace {

// Only the header's constants: the functions are the plugin's.
int imreadFlags(ImageChannels channels) {
  return channels == ImageChannels::as_stored ? cv::IMREAD_UNCHANGED : cv::IMREAD_ANYDEPTH | cv::IMREAD_ANYCOLOR;
}

// Loaded by the first image read or written, never unloaded: the codecs' libraries stay for the
// process's life.
const detail::ImageCodecs& codecs() {
  return core::loadPlugin<detail::ImageCodecs>(BINPICK_IMAGE_CODECS_BESIDE_PROGRAM, BINPICK_IMAGE_CODECS_IN_BUILD,
                                               detail::kImageCodecsEntry, detail::kImageCodecsVersion,
                                               "cannot read or write image files: binpick's image-codecs plugin");
}

}  // namespace

cv::Mat readImageFile(const std::string& path, ImageChannels channels) {
  return codecs().read(path, imreadFlags(channels));
}

cv::Mat decodeImage(const std::string& bytes, ImageChannels channels) {
  return codecs().decode(bytes, imreadFlags(channels));
}

void writeImageFile(const std::string& path, const cv::Mat& image) {
  std::string why;
  if (!codecs().write(path, image, why)) {
    throw core::Error(path + ": cannot write the image" + (why.empty() ? "" : ": " + why));
  }
}

std::string encodePng(const cv::Mat& image, int compression_level) {
  return codecs().encode_png(image, compression_level);
}

}  // namespace binpick::io
