// Another rig's pattern images as a Capture (capture_import.hpp).
#include "binpick/io/capture_import.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <opencv2/imgproc.hpp>

#include "binpick/core/error.hpp"
#include "binpick/io/image_file.hpp"

namespace binpick::io {
namespace {

namespace fs = std::filesystem;

bool isDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

// The digit run of `text` from `begin`, without leading zeros, and where it ends.
std::string digitRun(const std::string& text, std::size_t begin, std::size_t& end) {
  end = begin;
  while (end < text.size() && isDigit(text[end])) ++end;
  const std::size_t first = std::min(text.find_first_not_of('0', begin), end);
  return text.substr(first, end - first);
}

// * and ? against a whole file name.
bool globMatch(const char* pattern, const char* name) {
  if (*pattern == '\0') return *name == '\0';
  if (*pattern == '*') return globMatch(pattern + 1, name) || (*name != '\0' && globMatch(pattern, name + 1));
  if (*name == '\0') return false;
  return (*pattern == '?' || *pattern == *name) && globMatch(pattern + 1, name + 1);
}

bool isImageFile(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".png" || extension == ".bmp" || extension == ".tif" || extension == ".tiff";
}

// A grey image; a colour file (a BMP saved as RGB) is turned grey.
cv::Mat readGreyImage(const std::string& path) {
  cv::Mat image = readImageFile(path, ImageChannels::without_alpha);
  if (image.empty()) throw core::Error(path + ": not a readable PNG, BMP or TIFF image");
  if (image.channels() == 3) cv::cvtColor(image, image, cv::COLOR_BGR2GRAY);
  if (image.channels() == 4) cv::cvtColor(image, image, cv::COLOR_BGRA2GRAY);
  if (image.channels() != 1 || (image.depth() != CV_8U && image.depth() != CV_16U)) {
    throw core::Error(path + ": an 8- or 16-bit grey or colour image is needed");
  }
  return image;
}

// The decoder's thresholds are in 8-bit counts of full scale: 16-bit values in the low bits
// would all look dark. Returns the shift applied.
int toHighBits(std::vector<cv::Mat>& images) {
  if (images.front().depth() != CV_16U) return 0;
  double brightest = 0.0;
  for (const cv::Mat& image : images) {
    double max = 0.0;
    cv::minMaxLoc(image, nullptr, &max);
    brightest = std::max(brightest, max);
  }
  int shift = 0;
  while (shift < 8 && brightest * (1 << (shift + 1)) <= 65535.0) ++shift;
  for (cv::Mat& image : images) image *= (1 << shift);
  return shift;
}

}  // namespace

bool naturalLess(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (isDigit(a[i]) && isDigit(b[j])) {
      std::size_t i_end = 0, j_end = 0;
      const std::string x = digitRun(a, i, i_end), y = digitRun(b, j, j_end);
      if (x.size() != y.size()) return x.size() < y.size();
      if (x != y) return x < y;
      i = i_end;
      j = j_end;
      continue;
    }
    if (a[i] != b[j]) return a[i] < b[j];
    ++i;
    ++j;
  }
  return a.size() - i < b.size() - j;
}

std::vector<std::string> listImageFiles(const std::string& directory, const std::string& glob) {
  if (!fs::is_directory(directory)) throw core::Error(directory + ": no such directory");
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(directory)) {
    if (!entry.is_regular_file()) continue;
    const std::string name = entry.path().filename().string();
    if (glob.empty() ? isImageFile(entry.path()) : globMatch(glob.c_str(), name.c_str())) names.push_back(name);
  }
  std::sort(names.begin(), names.end(), naturalLess);
  std::vector<std::string> files;
  for (const std::string& name : names) files.push_back((fs::path(directory) / name).string());
  return files;
}

Capture importImages(const std::vector<std::string>& files, const PatternSetSpec& spec,
                     const std::vector<std::string>& patterns, const std::string& source, int* shifted_bits) {
  if (files.empty() || files.size() != patterns.size()) {
    throw core::Error(std::to_string(files.size()) + " image files for " + std::to_string(patterns.size()) +
                      " patterns");
  }
  Capture capture;
  for (const std::string& file : files) {
    capture.images.push_back(readGreyImage(file));
    const cv::Mat& first = capture.images.front();
    const cv::Mat& image = capture.images.back();
    if (image.size() != first.size() || image.depth() != first.depth()) {
      throw core::Error(file + ": " + std::to_string(image.cols) + "x" + std::to_string(image.rows) + " at " +
                        std::to_string(image.elemSize1() * 8) + " bits, unlike " + files.front());
    }
  }
  const int shift = toHighBits(capture.images);
  if (shifted_bits != nullptr) *shifted_bits = shift;
  CaptureMetadata& m = capture.metadata;
  m.source = source;
  m.timestamp = utcTimestamp();
  m.image_width = capture.images.front().cols;
  m.image_height = capture.images.front().rows;
  m.bit_depth = capture.images.front().depth() == CV_16U ? 16 : 8;
  m.pattern_set = spec;
  m.patterns = patterns;
  return capture;
}

}  // namespace binpick::io
