// ForeignStorage: the numbers of another tool's FileStorage file, read without trusting its sizes.
#include "foreign_storage.hpp"

#include <cctype>
#include <cmath>
#include <fstream>

#include "binpick/core/error.hpp"

namespace binpick::io::detail {
namespace {

// More numbers than any calibration holds (thousands of board views, 3 to 9 values each): a
// header claiming more is corrupt, and refusing it keeps OpenCV from allocating for it.
constexpr long kMaxValues = 1 << 16;
// Lists of matrices of lists: deeper nesting is not a calibration.
constexpr int kMaxDepth = 3;

// What went wrong reading one node; the caller names the file and key.
struct NodeError {
  std::string what;
};

bool isNumber(const cv::FileNode& node) { return node.isInt() || node.isReal(); }

// The channel count of an OpenCV type string ("d", "3d", "2f"): its leading digits, 1 if none.
int channelsOf(const std::string& dt) {
  int channels = 0;
  std::size_t i = 0;
  for (; i < dt.size() && std::isdigit(static_cast<unsigned char>(dt[i])) && channels <= kMaxValues; ++i) {
    channels = 10 * channels + (dt[i] - '0');
  }
  return i == 0 ? 1 : channels;
}

int sizeValue(const cv::FileNode& node) {
  if (!node.isInt()) throw NodeError{"its matrix sizes are not integers"};
  const int size = static_cast<int>(node);
  if (size < 1 || size > kMaxValues) throw NodeError{"its matrix size " + std::to_string(size) + " is out of range"};
  return size;
}

long product(const std::vector<int>& shape) {
  long count = 1;
  for (int size : shape) count *= size;  // each size <= kMaxValues, checked after every step below
  return count;
}

// The sizes of an OpenCV matrix map (rows and cols, or n-dimensional sizes), channels last.
std::vector<int> matrixShape(const cv::FileNode& node) {
  std::vector<int> shape;
  const cv::FileNode sizes = node["sizes"];
  if (!sizes.empty()) {
    if (!sizes.isSeq() || sizes.size() < 1 || sizes.size() > 4) throw NodeError{"its 'sizes' are not 1 to 4 sizes"};
    for (const cv::FileNode& size : sizes) {
      shape.push_back(sizeValue(size));
      if (product(shape) > kMaxValues) throw NodeError{"it claims more than 65536 values"};
    }
  } else {
    if (node["rows"].empty() || node["cols"].empty()) throw NodeError{"it is a map but not an OpenCV matrix"};
    shape = {sizeValue(node["rows"]), sizeValue(node["cols"])};
  }
  const cv::FileNode dt = node["dt"];
  const int channels = dt.isString() ? channelsOf(static_cast<std::string>(dt)) : 1;
  if (channels < 1 || channels > kMaxValues) throw NodeError{"its element type is not a number type"};
  if (channels > 1) shape.push_back(channels);
  if (product(shape) > kMaxValues) throw NodeError{"it claims more than 65536 values"};
  return shape;
}

void readNode(const cv::FileNode& node, int depth, std::vector<int>& shape, std::vector<double>& values);

// The data of an OpenCV matrix map, read as numbers straight from the file: nothing is allocated
// from the header before the data is known to match it.
void readMatrixMap(const cv::FileNode& node, std::vector<int>& shape, std::vector<double>& values) {
  shape = matrixShape(node);
  const cv::FileNode data = node["data"];
  if (!data.isSeq()) throw NodeError{"its data is not a list of numbers"};
  if (static_cast<long>(data.size()) != product(shape)) {
    throw NodeError{"its data holds " + std::to_string(data.size()) + " values for " + std::to_string(product(shape)) +
                    " elements"};
  }
  for (const cv::FileNode& value : data) {
    if (!isNumber(value)) throw NodeError{"its data is not a list of numbers"};
    values.push_back(static_cast<double>(value));
  }
}

// A list: of numbers (shape {n}), or of equally shaped elements (shape {n, element shape}).
void readList(const cv::FileNode& node, int depth, std::vector<int>& shape, std::vector<double>& values) {
  const int count = static_cast<int>(node.size());
  if (count < 1) throw NodeError{"it is an empty list"};
  if (count > kMaxValues) throw NodeError{"it holds more than 65536 values"};
  std::vector<int> element_shape;
  for (int i = 0; i < count; ++i) {
    std::vector<int> this_shape;
    readNode(node[i], depth + 1, this_shape, values);
    if (i > 0 && this_shape != element_shape) throw NodeError{"its list elements differ in size"};
    element_shape = this_shape;
    if (static_cast<long>(values.size()) > kMaxValues) throw NodeError{"it holds more than 65536 values"};
  }
  shape = {count};
  shape.insert(shape.end(), element_shape.begin(), element_shape.end());
}

void readNode(const cv::FileNode& node, int depth, std::vector<int>& shape, std::vector<double>& values) {
  if (depth > kMaxDepth) throw NodeError{"it is nested too deeply"};
  if (isNumber(node)) {
    shape.clear();
    values.push_back(static_cast<double>(node));
  } else if (node.isSeq()) {
    readList(node, depth, shape, values);
  } else if (node.isMap()) {
    readMatrixMap(node, shape, values);
  } else {
    throw NodeError{"it is not a number, a list of numbers or an OpenCV matrix"};
  }
}

}  // namespace

std::string StoredNumbers::shapeText() const {
  if (shape.empty()) return "1";
  std::string text;
  for (int size : shape) text += (text.empty() ? "" : "x") + std::to_string(size);
  return text;
}

ForeignStorage::ForeignStorage(const std::string& path) : path_(path) {
  if (!std::ifstream(path)) fail("cannot open the calibration file");
  try {
    // The format (XML, YAML, JSON) is told by the file's first bytes, or else by its extension.
    storage_.open(path, cv::FileStorage::READ);
  } catch (const cv::Exception& e) {
    fail("not an OpenCV FileStorage file (XML, YAML or JSON): " + e.err);
  }
  if (!storage_.isOpened()) fail("not an OpenCV FileStorage file (XML, YAML or JSON)");
  // Looking a key up in a document that is a list or a scalar throws a cv::Exception.
  if (!storage_.root().isMap()) fail("not an OpenCV FileStorage file (no map of keys)");
}

void ForeignStorage::fail(const std::string& what) const { throw core::Error(path_ + ": " + what); }

bool ForeignStorage::has(const std::string& key) const { return !storage_[key].empty(); }

std::vector<std::string> ForeignStorage::present(const std::vector<std::string>& candidates) const {
  std::vector<std::string> found;
  for (const std::string& key : candidates) {
    if (has(key)) found.push_back(key);
  }
  return found;
}

StoredNumbers ForeignStorage::numbers(const std::string& key) const {
  const cv::FileNode node = storage_[key];
  if (node.empty()) fail("missing key '" + key + "'");
  StoredNumbers stored;
  stored.key = key;
  try {
    readNode(node, 0, stored.shape, stored.values);
  } catch (const NodeError& error) {
    fail("'" + key + "' cannot be read: " + error.what);
  } catch (const cv::Exception& e) {
    fail("'" + key + "' cannot be read: " + e.err);
  }
  for (double value : stored.values) {
    if (!std::isfinite(value)) fail("'" + key + "' holds a non-finite value");
  }
  return stored;
}

}  // namespace binpick::io::detail
