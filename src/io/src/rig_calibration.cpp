// calib.yaml: the rig in OpenCV FileStorage YAML, read with every key, size and value checked,
// and the calibration's quality beside it.
#include "binpick/io/rig_calibration.hpp"

#include <Eigen/LU>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <opencv2/core.hpp>
#include <sstream>
#include <vector>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include "binpick/core/error.hpp"
#include "binpick/core/file.hpp"
#include "rig_calibration_quality.hpp"

namespace binpick::io {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) { throw core::Error(path + ": " + what); }

// The largest matrix side read: a 3x3 rotation or lens matrix, 4 or 5 distortion values.
constexpr int kMaxMatrixSide = 16;

// OpenCV sizes its allocation from a matrix's rows and cols (or sizes) before it looks at the
// data, so a corrupt header claiming 10^5 x 10^5 would allocate gigabytes: the header is checked
// first.
void checkMatrixHeader(const cv::FileNode& node, const std::string& path, const std::string& key) {
  if (!node.isMap() || !node["sizes"].empty() || !node["rows"].isInt() || !node["cols"].isInt() ||
      !node["data"].isSeq()) {
    fail(path, "'" + key + "' is not an OpenCV matrix (rows, cols, dt and data)");
  }
  const int rows = static_cast<int>(node["rows"]);
  const int cols = static_cast<int>(node["cols"]);
  if (rows < 1 || cols < 1 || rows > kMaxMatrixSide || cols > kMaxMatrixSide) {
    fail(path, "'" + key + "' must be at most " + std::to_string(kMaxMatrixSide) + "x" +
                   std::to_string(kMaxMatrixSide) + " (got " + std::to_string(rows) + "x" + std::to_string(cols) + ")");
  }
}

cv::Mat readMatrix(const cv::FileStorage& fs, const std::string& path, const std::string& key) {
  const cv::FileNode node = fs[key];
  if (node.empty()) fail(path, "missing key '" + key + "'");
  checkMatrixHeader(node, path, key);
  cv::Mat m;
  try {
    node >> m;
  } catch (const cv::Exception&) {
    fail(path, "'" + key + "' is not an OpenCV matrix");
  }
  if (m.empty()) fail(path, "'" + key + "' is not an OpenCV matrix");
  // A multi-channel matrix would otherwise be read element by element as if it had one.
  if (m.channels() != 1) fail(path, "'" + key + "' must have one channel");
  m.convertTo(m, CV_64F);
  for (auto it = m.begin<double>(); it != m.end<double>(); ++it) {
    if (!std::isfinite(*it)) fail(path, "'" + key + "' holds a non-finite value");
  }
  return m;
}

cv::Mat readMatrixOfSize(const cv::FileStorage& fs, const std::string& path, const std::string& key, int rows,
                         int cols) {
  const cv::Mat m = readMatrix(fs, path, key);
  if (m.rows != rows || m.cols != cols) {
    std::ostringstream message;
    message << "'" << key << "' must be " << rows << "x" << cols << " (got " << m.rows << "x" << m.cols << ")";
    fail(path, message.str());
  }
  return m;
}

int readInt(const cv::FileStorage& fs, const std::string& path, const std::string& key) {
  const cv::FileNode node = fs[key];
  if (node.empty()) fail(path, "missing key '" + key + "'");
  if (!node.isInt()) fail(path, "'" + key + "' must be an integer");
  return static_cast<int>(node);
}

LensIntrinsics readLens(const cv::FileStorage& fs, const std::string& path, const std::string& device) {
  LensIntrinsics lens;
  lens.width = readInt(fs, path, device + "_width");
  lens.height = readInt(fs, path, device + "_height");
  const cv::Mat k = readMatrixOfSize(fs, path, device + "_matrix", 3, 3);
  if (k.at<double>(0, 1) != 0.0 || k.at<double>(1, 0) != 0.0 || k.at<double>(2, 0) != 0.0 ||
      k.at<double>(2, 1) != 0.0 || k.at<double>(2, 2) != 1.0) {
    fail(path, "'" + device + "_matrix' must be [fx 0 cx; 0 fy cy; 0 0 1]");
  }
  lens.fx = k.at<double>(0, 0);
  lens.fy = k.at<double>(1, 1);
  lens.cx = k.at<double>(0, 2);
  lens.cy = k.at<double>(1, 2);
  const cv::Mat d = readMatrix(fs, path, device + "_distortion");
  const int count = static_cast<int>(d.total());
  if ((d.rows != 1 && d.cols != 1) || (count != 4 && count != 5)) {
    fail(path, "'" + device + "_distortion' must hold 4 or 5 values (k1 k2 p1 p2 [k3])");
  }
  for (int i = 0; i < count; ++i) lens.distortion[i] = d.at<double>(i);
  try {
    lens.validate(device);
  } catch (const core::Error& e) {
    fail(path, e.what());
  }
  return lens;
}

void writeLens(cv::FileStorage& fs, const std::string& device, const LensIntrinsics& lens) {
  fs << device + "_width" << lens.width << device + "_height" << lens.height;
  const cv::Mat k = (cv::Mat_<double>(3, 3) << lens.fx, 0.0, lens.cx, 0.0, lens.fy, lens.cy, 0.0, 0.0, 1.0);
  fs << device + "_matrix" << k;
  fs << device + "_distortion" << cv::Mat(1, 5, CV_64F, const_cast<double*>(lens.distortion.data()));
}

void writeRig(const std::string& path, const RigCalibration& rig, const RigCalibrationQuality* quality) {
  rig.validate();
  core::replaceFileAtomically(path, [&](const std::string& temporary) {
    cv::FileStorage fs(temporary, cv::FileStorage::WRITE | cv::FileStorage::FORMAT_YAML);
    if (!fs.isOpened()) fail(path, "cannot write the calibration file");
    writeLens(fs, "camera", rig.camera);
    writeLens(fs, "projector", rig.projector);
    cv::Mat r(3, 3, CV_64F), t(3, 1, CV_64F);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) r.at<double>(i, j) = rig.T_projector_camera.linear()(i, j);
      t.at<double>(i) = rig.T_projector_camera.translation()(i);
    }
    fs << "R" << r << "T" << t;
    if (quality) detail::writeQuality(fs, *quality);
  });
}

// The deepest nesting in calib.yaml: the root map, `quality`, its `views` list, a view's map.
constexpr int kMaxCalibrationDepth = 4;

// A key as OpenCV writes them: a letter or '_', then letters, digits, '_' or '-'. OpenCV's parser
// mishandles others (an empty key, or one starting with ':', makes it read before the key).
bool isOpenCvName(const YAML::Node& key) {
  if (!key.IsScalar() || key.Scalar().empty()) return false;
  const std::string& name = key.Scalar();
  if (!std::isalpha(static_cast<unsigned char>(name[0])) && name[0] != '_') return false;
  for (const char c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') return false;
  }
  return true;
}

// "" when `node` and what it holds nest at most `levels` deep with names for keys.
std::string nestingDefect(const YAML::Node& node, int levels) {
  if (!node.IsMap() && !node.IsSequence()) return "";
  if (levels == 0) return "nested deeper than a calibration file";
  for (const auto& entry : node) {
    const YAML::Node& value = node.IsMap() ? entry.second : static_cast<const YAML::Node&>(entry);
    if (node.IsMap() && !isOpenCvName(entry.first)) return "a key that is not a name";
    const std::string defect = nestingDefect(value, levels - 1);
    if (!defect.empty()) return defect;
  }
  return "";
}

// Follows a YAML document without building it: enough to tell whether there is another one.
class IgnoredEvents : public YAML::EventHandler {
 public:
  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t, const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

// Whether the text holds a second document. Asked of yaml-cpp's parser once, not by
// YAML::LoadAll, which (yaml-cpp 0.7) loops forever allocating on a stray ',' after a block.
bool hasSecondDocument(const std::string& text) {
  std::istringstream stream(text);
  YAML::Parser parser(stream);
  IgnoredEvents ignored;
  parser.HandleNextDocument(ignored);
  return parser.HandleNextDocument(ignored);
}

// OpenCV's FileStorage parser (4.6) loops forever on some malformed YAML (several documents
// after an indented line) and reads out of bounds on others (an empty key), so only text that
// yaml-cpp reads as one document holding a map of the calibration file's shape reaches it. ""
// when the text passes, else what is wrong.
std::string calibrationShapeDefect(const std::string& text) {
  YAML::Node document;
  try {
    document = YAML::Load(text);
    if (hasSecondDocument(text)) return "more than one YAML document";
  } catch (const YAML::Exception& e) {
    return "line " + std::to_string(e.mark.line + 1) + ": " + e.msg;
  }
  if (!document.IsMap()) return "no map of keys";
  return nestingDefect(document, kMaxCalibrationDepth);
}

}  // namespace

namespace detail {

cv::FileStorage openForReading(const std::string& path) {
  std::string text;
  try {
    text = core::readFile(path);
  } catch (const core::Error& e) {
    std::string reason = e.what();
    if (reason.compare(0, path.size() + 2, path + ": ") == 0) reason.erase(0, path.size() + 2);
    fail(path, "cannot open the calibration file (" + reason + ")");
  }
  const std::string defect = calibrationShapeDefect(text);
  if (!defect.empty()) fail(path, "not an OpenCV FileStorage YAML file (" + defect + ")");
  cv::FileStorage fs;
  try {
    fs.open(text, cv::FileStorage::READ | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  } catch (const std::exception&) {  // cv::Exception, and what OpenCV's parser lets escape
    fail(path, "not an OpenCV FileStorage YAML file");
  }
  if (!fs.isOpened()) fail(path, "not an OpenCV FileStorage YAML file");
  // Looking a key up in a document that is a list or a scalar throws a cv::Exception.
  if (!fs.root().isMap()) fail(path, "not an OpenCV FileStorage YAML file (no map of keys)");
  return fs;
}

}  // namespace detail

void RigCalibration::validate() const {
  camera.validate("camera");
  projector.validate("projector");
  const Eigen::Matrix3d r = T_projector_camera.linear();
  if (!r.allFinite() || !T_projector_camera.translation().allFinite()) {
    throw core::Error("rig R and T must be finite");
  }
  if ((r * r.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-6 || r.determinant() < 0.0) {
    throw core::Error("rig R must be a rotation (orthonormal, determinant +1)");
  }
}

RigCalibration readRigCalibration(const std::string& path) {
  cv::FileStorage fs = detail::openForReading(path);
  RigCalibration rig;
  cv::Mat r, t;
  try {
    rig.camera = readLens(fs, path, "camera");
    rig.projector = readLens(fs, path, "projector");
    r = readMatrixOfSize(fs, path, "R", 3, 3);
    t = readMatrix(fs, path, "T");
  } catch (const cv::Exception& e) {
    fail(path, "malformed OpenCV FileStorage content: " + e.err);
  }
  if (t.total() != 3 || (t.rows != 1 && t.cols != 1)) fail(path, "'T' must hold 3 values");
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) rig.T_projector_camera.matrix()(i, j) = r.at<double>(i, j);
    rig.T_projector_camera.matrix()(i, 3) = t.at<double>(i);
  }
  try {
    rig.validate();
  } catch (const core::Error& e) {
    fail(path, e.what());
  }
  return rig;
}

void writeRigCalibration(const std::string& path, const RigCalibration& rig) { writeRig(path, rig, nullptr); }

void writeRigCalibration(const std::string& path, const RigCalibration& rig, const RigCalibrationQuality& quality) {
  writeRig(path, rig, &quality);
}

}  // namespace binpick::io
