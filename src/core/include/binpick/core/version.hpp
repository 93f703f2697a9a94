#pragma once
// The version the programs report (`--version`): the project's version and the git revision it
// was built from, e.g. "0.1.0 (git 47b5d18a2c)". Defined in a file generated at every build
// (cmake/WriteVersion.cmake), in the binpick_version library that only the executables link.
namespace binpick::core {

const char* versionText();

}  // namespace binpick::core
