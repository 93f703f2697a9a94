#pragma once
// Image files (PNG, BMP, TIFF, JPEG and whatever else OpenCV's codecs read), through a plugin that
// binpick loads the first time an image is read or written. Linked into the programs, OpenCV's
// codecs and the libraries they need (GDAL, DICOM, HEIF: about 140) took 80 ms to load at every
// start of every program, longer than detecting a pile; `binpick detect` on a cloud file and
// binpickd's start need none of them. Thread-safe.
//
// Every function throws core::Error when the plugin cannot be loaded, naming it and why. An image
// that cannot be read is an empty matrix, as from OpenCV, so that each reader says in its own
// words what the file was for.
#include <opencv2/core.hpp>
#include <string>

namespace binpick::io {

// Which channels of a file an image keeps; both keep the file's bit depth.
enum class ImageChannels {
  as_stored,      // every channel, alpha included
  without_alpha,  // grey or colour, an alpha channel dropped
};

// The image in the file; an empty matrix when it is missing or cannot be decoded.
cv::Mat readImageFile(const std::string& path, ImageChannels channels = ImageChannels::as_stored);

// The image held in a file's bytes; an empty matrix when they cannot be decoded.
cv::Mat decodeImage(const std::string& bytes, ImageChannels channels = ImageChannels::as_stored);

// Writes the image in the format the path's extension names. Throws core::Error naming the path
// (and OpenCV's reason when it has one: no writer for the extension, a depth the format lacks)
// when it cannot be written.
void writeImageFile(const std::string& path, const cv::Mat& image);

// The bytes of a PNG file of the image at zlib's compression level (0-9); empty when the image
// cannot be encoded as PNG (a depth or channel count PNG does not have).
std::string encodePng(const cv::Mat& image, int compression_level = 3);

}  // namespace binpick::io
