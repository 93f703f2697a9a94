#pragma once
// Whole text files for the hand-eye files (poses.txt, hand_eye.yaml).
#include <string>

namespace binpick::calibration::detail {

// Throws binpick::Error "PATH: cannot read ..." when the file cannot be opened.
std::string readTextFile(const std::string& path);
// Written to PATH.tmp and renamed: a reader sees the old file or the whole new one. Throws
// binpick::Error "PATH: cannot write ..." (creating the parent directory when missing).
void writeTextFileAtomically(const std::string& path, const std::string& text);

}  // namespace binpick::calibration::detail
