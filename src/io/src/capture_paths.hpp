#pragma once
// Internal: file names inside a capture directory, shared by the metadata and image code.
#include <string>

#include "binpick/io/capture.hpp"

namespace binpick::io::capture_detail {

std::string metadataPath(const std::string& directory);     // DIR/capture.json
std::string imagesDirectory(const std::string& directory);  // DIR/images
// "images/007_gray_col_03.png" for pattern 7 named "gray_col_03".
std::string imageName(std::size_t index, const std::string& pattern);
// True for "images/<file>.png" with no further directory and no "..": a metadata file cannot point
// outside its capture.
bool isPlainImageName(const std::string& name);

// Throws core::Error "PATH: ..." when the metadata is incomplete or inconsistent.
void checkMetadata(const CaptureMetadata& metadata, const std::string& path);
void writeCaptureMetadata(const std::string& directory, const CaptureMetadata& metadata);

}  // namespace binpick::io::capture_detail
