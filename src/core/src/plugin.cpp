#include "binpick/core/plugin.hpp"

#include <dlfcn.h>

#include <filesystem>

namespace binpick::core {

std::string pluginPath(const std::string& beside_program, const std::string& in_build) {
  std::error_code error;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    const std::filesystem::path installed = program.parent_path() / beside_program;
    if (std::filesystem::exists(installed, error)) return installed.lexically_normal().string();
  }
  return in_build;
}

const void* loadPluginTable(const std::string& path, const char* entry, const std::string& what) {
  void* plugin = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (plugin == nullptr) throw Error(what + " (" + path + ") could not be loaded: " + dlerror());
  using Entry = const void* (*)();
  const auto function = reinterpret_cast<Entry>(dlsym(plugin, entry));
  if (function == nullptr) throw Error(what + " (" + path + ") has no " + entry);
  const void* table = function();
  if (table == nullptr) throw Error(what + " (" + path + ") is from another build of binpick (reinstall it)");
  return table;
}

}  // namespace binpick::core
