#pragma once
// Reading the cv::FileStorage files of other tools (XML, YAML or JSON, told apart by content):
// keys looked up among several spellings, and numbers read whatever shape they were written in
// (an OpenCV matrix, an n-dimensional one from a numpy array, a plain list or list of lists, a
// single number). Every size is checked before OpenCV allocates anything: a corrupt header must
// not claim gigabytes. Errors are core::Error "PATH: ...".
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

namespace binpick::io::detail {

// Numbers as stored: `shape` the matrix's sizes ({rows, cols}, the n-dimensional sizes with the
// channels last when there are several, {n} for a list, {} for a single number), `values` in
// row-major order.
struct StoredNumbers {
  std::string key;
  std::vector<int> shape;
  std::vector<double> values;
  std::string shapeText() const;  // "3x1", "5", "1"
};

class ForeignStorage {
 public:
  // Throws when the file cannot be opened or is not a FileStorage map of keys.
  explicit ForeignStorage(const std::string& path);

  const std::string& path() const { return path_; }
  [[noreturn]] void fail(const std::string& what) const;

  bool has(const std::string& key) const;
  // Those of `candidates` the file has at its top level, in the candidates' order.
  std::vector<std::string> present(const std::vector<std::string>& candidates) const;
  // Throws naming the key when it is missing, holds something other than numbers, more of them
  // than a calibration has, or a non-finite one.
  StoredNumbers numbers(const std::string& key) const;

 private:
  std::string path_;
  cv::FileStorage storage_;
};

}  // namespace binpick::io::detail
