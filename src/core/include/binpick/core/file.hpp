#pragma once
// Whole files. Reading gives all bytes or an error naming the file. Writing replaces a file whole:
// whoever reads PATH (a robot script polling for a port file, a second service sharing a model
// cache, a user opening calib.yaml) sees the old file or the complete new one, never a part. The
// bytes go to a temporary file beside PATH, unique to this process and call, which is then renamed
// over PATH (atomic within one file system). Thread-safe.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
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

// A file's bytes mapped read-only into memory, all pages faulted in at once: a large file (a model
// cache of hundreds of megabytes) is ready without a read or a copy, and processes mapping one
// file share its pages with the page cache. The mapping lives as long as the returned pointer
// (share it with whatever views the bytes). Writers replace files by rename (writeFileAtomically),
// so a mapped file is never changed under its readers. Throws core::Error naming PATH when it does
// not exist, is not a regular file or cannot be mapped.
class MappedFile {
 public:
  static std::shared_ptr<const MappedFile> open(const std::string& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  const uint8_t* data() const { return data_; }
  std::size_t size() const { return size_; }

 private:
  MappedFile(const uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  const uint8_t* data_;
  std::size_t size_;
};

}  // namespace binpick::core
