#pragma once
// Another rig's pattern images as a Capture: whatever their format (PNG, BMP or TIFF, 8 or 16
// bit, grey or colour) and names, in the order the rig's sequence lists them. writeCapture then
// makes a capture directory of it. Stateless: thread-safe.
#include <string>
#include <vector>

#include "binpick/io/capture.hpp"

namespace binpick::io {

// The image files of `directory` in natural name order ("img10" after "img9"): those matching
// `glob` (* and ?, against the file name) when given, else every .png, .bmp, .tif and .tiff.
// Throws core::Error when the directory does not exist.
std::vector<std::string> listImageFiles(const std::string& directory, const std::string& glob = "");

// "img10" after "img9": digit runs compare as numbers, the rest as text.
bool naturalLess(const std::string& a, const std::string& b);

// The files as a capture showing `patterns` (one per file, in order) of `spec`. Colour images
// are turned grey. 16-bit images whose values use only the low bits (a 10- or 12-bit camera's
// TIFF) are shifted up to the high bits, as captures hold them (docs/capture-format.md);
// `shifted_bits` (when given) says by how many. Throws core::Error naming the file on an
// unreadable image, one of another size or depth than the first, or a count unlike `patterns`'.
Capture importImages(const std::vector<std::string>& files, const PatternSetSpec& spec,
                     const std::vector<std::string>& patterns, const std::string& source, int* shifted_bits = nullptr);

}  // namespace binpick::io
