// Image files through the image-codecs plugin (binpick/io/image_file.hpp says why a plugin).
#include "binpick/io/image_file.hpp"

#include <dlfcn.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "binpick/core/error.hpp"
#include "image_codecs_abi.hpp"

namespace binpick::io {
namespace {

// Only the header's constants: the functions are the plugin's.
int imreadFlags(ImageChannels channels) {
  return channels == ImageChannels::as_stored ? cv::IMREAD_UNCHANGED : cv::IMREAD_ANYDEPTH | cv::IMREAD_ANYCOLOR;
}

// An installed program's plugin is in lib/binpick beside its bin (wherever the package was
// unpacked); a program of the build tree uses the build's. Both paths come from the build.
std::string pluginPath() {
  std::error_code error;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    const std::filesystem::path installed = program.parent_path() / BINPICK_IMAGE_CODECS_BESIDE_PROGRAM;
    if (std::filesystem::exists(installed, error)) return installed.lexically_normal().string();
  }
  return BINPICK_IMAGE_CODECS_IN_BUILD;
}

[[noreturn]] void failToLoad(const std::string& path, const std::string& why) {
  throw core::Error("cannot read or write image files: binpick's image codecs (" + path + ") " + why);
}

// Loaded once, never unloaded: the codecs' libraries stay for the process's life.
const detail::ImageCodecs& loadCodecs() {
  const std::string path = pluginPath();
  void* plugin = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (plugin == nullptr) failToLoad(path, std::string("could not be loaded: ") + dlerror());
  using Entry = const detail::ImageCodecs* (*)();
  const auto entry = reinterpret_cast<Entry>(dlsym(plugin, detail::kImageCodecsEntry));
  if (entry == nullptr) failToLoad(path, std::string("have no ") + detail::kImageCodecsEntry);
  const detail::ImageCodecs* codecs = entry();
  if (codecs == nullptr || codecs->version != detail::kImageCodecsVersion) {
    failToLoad(path, "are from another build of binpick (reinstall it)");
  }
  return *codecs;
}

const detail::ImageCodecs& codecs() {
  // A failed load throws out of the initialisation, so the next call tries again.
  static const detail::ImageCodecs& loaded = loadCodecs();
  return loaded;
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
