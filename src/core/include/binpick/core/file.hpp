#pragma once
// Whole files. Reading gives all bytes or an error naming the file. Writing replaces a file whole:
// whoever reads PATH (a robot script polling for a port file, a second service sharing a model
// cache, a user opening calib.yaml) sees the old file or the complete new one, never a part. The
// bytes go to a temporary file beside PATH, unique to this process and call, which is then renamed
// over PATH (atomic within one file system). Thread-safe.
#include <functional>
#include <string>
#include <string_view>

namespace binpick::core {

// The file's bytes, in one read; throws core::Error naming PATH when it does not exist, is not a
// regular file (a directory, a device) or cannot be read whole.
std::string readFile(const std::string& path);

// Whether a missing directory of PATH is an error (settings and caches go where they are told) or
// is created (a calibration's result directory, DIR/truth of a rendered session).
enum class ParentDirectory { MustExist, Create };

// Writes BYTES as PATH. Throws core::Error "PATH: cannot write the file: REASON" (the temporary
// file removed) when anything fails.
void writeFileAtomically(const std::string& path, std::string_view bytes,
                         ParentDirectory parent = ParentDirectory::MustExist);

// For writers that need a file name of their own (OpenCV's FileStorage, image encoders): calls
// write(TEMPORARY) and renames TEMPORARY over PATH. Whatever write() throws propagates after the
// temporary file is removed.
void replaceFileAtomically(const std::string& path, const std::function<void(const std::string& temporary)>& write);

}  // namespace binpick::core
