// Whole text files, written atomically.
#include "hand_eye_text_file.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "binpick/io/error.hpp"

namespace binpick::calibration::detail {

std::string readTextFile(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(path + ": cannot read the file");
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

void writeTextFileAtomically(const std::string& path, const std::string& text) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  std::error_code error;
  if (target.has_parent_path()) fs::create_directories(target.parent_path(), error);
  const std::string partial = path + ".tmp";
  {
    std::ofstream file(partial, std::ios::binary | std::ios::trunc);
    file << text;
    file.flush();
    if (!file) throw Error(path + ": cannot write the file");
  }
  fs::rename(partial, target, error);
  if (error) {
    const std::string why = error.message();
    fs::remove(partial, error);
    throw Error(path + ": cannot write the file: " + why);
  }
}

}  // namespace binpick::calibration::detail
