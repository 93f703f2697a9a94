#pragma once
// binpick's own plugins: a part of a program that links libraries most runs never need (OpenCV's
// image codecs, cpp-httplib with OpenSSL, Aravis with GLib), built as a module beside the programs
// and loaded on first use, so that every start does not pay for loading and initialising those
// libraries. A plugin hands over one table of functions from a C entry (no C++ name mangling for
// dlsym) whose first member is `int version`; both sides compile the table from one header in the
// same build, and the version refuses a plugin left from another build.
#include <string>

#include "binpick/core/error.hpp"

namespace binpick::core {

// Where a plugin is: an installed program's in lib/binpick beside its bin (`beside_program`,
// relative to the program's directory, wherever the package was unpacked); a program of the build
// tree uses the build's (`in_build`). Both paths come from the build.
std::string pluginPath(const std::string& beside_program, const std::string& in_build);

// dlopen()s PATH and returns what its ENTRY() returns. Throws core::Error
// "WHAT (PATH) could not be loaded: ..." (or "has no ENTRY", or "is from another build of binpick")
// when the plugin is missing, broken or of another version. Never unloaded: the libraries it
// brought stay for the process's life.
const void* loadPluginTable(const std::string& path, const char* entry, const std::string& what);

// The plugin's table, loaded and checked by the first call for this Table (pluginPath, then
// loadPluginTable) and kept for the process's life. A failed load throws, and the next call tries
// again. Thread-safe.
template <typename Table>
const Table& loadPlugin(const std::string& beside_program, const std::string& in_build, const char* entry, int version,
                        const std::string& what) {
  static const Table& loaded = [&]() -> const Table& {
    const std::string path = pluginPath(beside_program, in_build);
    const auto* table = static_cast<const Table*>(loadPluginTable(path, entry, what));
    if (table->version != version) {
      throw Error(what + " (" + path + ") is from another build of binpick (reinstall it)");
    }
    return *table;
  }();
  return loaded;
}

}  // namespace binpick::core
