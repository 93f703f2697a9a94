// Fuzz target for capture directories: the input is DIR/capture.json, read by readCapture with
// the images it lists. The directory holds two small 8-bit images, images/000_white.png and
// images/001_black.png (4 x 3, what the seed corpus lists). When the input holds a NUL byte
// (which JSON text cannot), the bytes after it replace images/000_white.png for that input: the
// PNG checks before decoding are fuzzed too. A bad capture must be refused with a core::Error
// naming a file of it; an accepted one holds one image per pattern, each of the size and bit
// depth capture.json states. Built with libFuzzer (fuzz/run-libfuzzer.sh capture) and with the
// seeded driver (random_input_driver.cpp, test capture_fuzz_smoke).
#include "binpick/io/capture.hpp"
#include "binpick/io/image_file.hpp"
#include "fuzz_support.hpp"

namespace {

namespace fs = std::filesystem;
using namespace binpick;

// The two images every input may list, as PNG files: written once per process, and the first
// again after an input replaced it.
const std::string& whiteImage() {
  static const std::string bytes = io::encodePng(cv::Mat(3, 4, CV_8UC1, cv::Scalar(250)));
  return bytes;
}

fs::path captureDirectory() {
  static const fs::path directory = [] {
    const fs::path created = fuzz::scratchDirectory() / "capture";
    fs::create_directories(created / "images");
    fuzz::writeBytes(created / "images" / "001_black.png", io::encodePng(cv::Mat(3, 4, CV_8UC1, cv::Scalar(3))));
    return created;
  }();
  return directory;
}

void checkCapture(const io::Capture& capture, const std::string& input) {
  const io::CaptureMetadata& m = capture.metadata;
  fuzz::require(!m.patterns.empty() && capture.images.size() == m.patterns.size() && m.images.size() == m.patterns.size(),
                "readCapture", "one image per pattern", input);
  for (const cv::Mat& image : capture.images) {
    fuzz::require(image.cols == m.image_width && image.rows == m.image_height, "readCapture",
                  "images have the stated size", input);
    fuzz::require(image.type() == (m.bit_depth == 16 ? CV_16UC1 : CV_8UC1), "readCapture",
                  "images have the stated bit depth", input);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const fs::path directory = captureDirectory();
  const std::size_t nul = input.find('\0');
  fuzz::writeBytes(directory / "capture.json", input.substr(0, nul));
  fuzz::writeBytes(directory / "images" / "000_white.png", nul == std::string::npos ? whiteImage() : input.substr(nul + 1));
  io::Capture capture;
  // Every error names DIR or a file in it.
  if (fuzz::readsOrRefuses("readCapture", directory.string(), input,
                           [&] { capture = io::readCapture(directory.string(), 1); })) {
    checkCapture(capture, input);
  }
  return 0;
}
