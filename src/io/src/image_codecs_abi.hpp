#pragma once
// What the image-codecs plugin (plugin/image_codecs.cpp) hands to image_file.cpp: one table of
// functions, found by a C name so that dlsym needs no C++ mangling. Both sides are compiled from
// this header in the same build; the version refuses a plugin left from another build.
#include <opencv2/core.hpp>
#include <string>

namespace binpick::io::detail {

inline constexpr int kImageCodecsVersion = 1;
inline constexpr const char* kImageCodecsEntry = "binpick_image_codecs";

// The flags are OpenCV's cv::ImreadModes. None of the functions throws: write says why it failed
// in `why` (empty when OpenCV gives no reason).
struct ImageCodecs {
  int version;
  cv::Mat (*read)(const std::string& path, int flags);
  cv::Mat (*decode)(const std::string& bytes, int flags);
  bool (*write)(const std::string& path, const cv::Mat& image, std::string& why);
  std::string (*encode_png)(const cv::Mat& image, int compression_level);
};

}  // namespace binpick::io::detail

extern "C" const binpick::io::detail::ImageCodecs* binpick_image_codecs();
