// readOpenCvCalibration: another tool's cv::FileStorage calibration into a RigCalibration, every
// role looked up among the names tools use, every value checked, the translation into metres.
#include "binpick/io/opencv_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <utility>

#include "binpick/core/error.hpp"
#include "foreign_rig_pose.hpp"
#include "foreign_storage.hpp"

namespace binpick::io {
namespace {

using detail::ForeignStorage;
using detail::StoredNumbers;

struct RoleSpec {
  std::string role;
  std::string description;  // in errors: "no <description> (tried ...)"
  std::vector<std::string> names;
};

// The names are the ones calibration tools and their users write: OpenCV's samples
// (camera_matrix, distortion_coefficients; stereo_calib's M1 D1 M2 D2 R T), Moreno & Taubin's
// scan3d-capture (cam_K, cam_kc, proj_K, proj_kc), kamino410's procam-calibration (cam_int,
// cam_dist, proj_int, proj_dist, and its misspelt `roration`), and the obvious spellings.
const std::vector<RoleSpec>& roleSpecs() {
  static const std::vector<RoleSpec> specs = {
      {"camera_matrix",
       "camera matrix",
       {"cam_int", "camera_matrix", "cameraMatrix", "K1", "M1", "cam_K", "camera_intrinsic", "camera_intrinsics",
        "cam_matrix", "cam_mtx"}},
      {"camera_distortion",
       "camera distortion",
       {"cam_dist", "dist_coeffs", "distCoeffs", "D1", "camera_distortion", "distortion_coefficients", "cam_kc",
        "cam_distortion", "camera_dist"}},
      {"projector_matrix",
       "projector matrix",
       {"proj_int", "projector_matrix", "K2", "M2", "proj_K", "projector_intrinsic", "projector_intrinsics",
        "proj_matrix", "proj_mtx"}},
      {"projector_distortion",
       "projector distortion",
       {"proj_dist", "D2", "projector_distortion", "proj_kc", "proj_distortion", "projector_dist"}},
      {"rotation",
       "rotation from camera to projector",
       {"R", "rotation", "roration", "rot", "R_cam_proj", "rotation_matrix"}},
      {"translation",
       "translation from camera to projector",
       {"T", "translation", "trans", "t", "T_cam_proj", "translation_vector"}},
      {"camera_board_rotation",
       "camera's board rotation",
       {"cam_rvecs", "camera_rvecs", "cam_rvec", "cam_board_rotation"}},
      {"camera_board_translation",
       "camera's board translation",
       {"cam_tvecs", "camera_tvecs", "cam_tvec", "cam_board_translation"}},
      {"projector_board_rotation",
       "projector's board rotation",
       {"proj_rvecs", "projector_rvecs", "proj_rvec", "proj_board_rotation"}},
      {"projector_board_translation",
       "projector's board translation",
       {"proj_tvecs", "projector_tvecs", "proj_tvec", "proj_board_translation"}},
  };
  return specs;
}

const RoleSpec* findRole(const std::string& role) {
  for (const RoleSpec& spec : roleSpecs()) {
    if (spec.role == role) return &spec;
  }
  return nullptr;
}

const RoleSpec& roleSpec(const std::string& role) {
  if (const RoleSpec* spec = findRole(role)) return *spec;
  std::string roles;
  for (const std::string& name : openCvCalibrationRoles()) roles += (roles.empty() ? "" : ", ") + name;
  throw core::Error("unknown calibration role '" + role + "' (roles: " + roles + ")");
}

// A distortion role given as `none`: the lens has no distortion (the file stores none for it).
constexpr const char* kNoDistortion = "none";

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

// The file's key for `role`: the one given in the options, or the one of the role's names the
// file has; nullopt when it has none. Two of the names present is refused: which one the tool
// meant cannot be told.
std::optional<std::string> findRoleKey(const ForeignStorage& file, const OpenCvCalibrationOptions& options,
                                       const std::string& role) {
  const RoleSpec& spec = roleSpec(role);
  const auto given = options.keys.find(role);
  if (given != options.keys.end()) {
    if (given->second == kNoDistortion || file.has(given->second)) return given->second;
    file.fail("no key '" + given->second + "' for the " + spec.description + " (given by --key " + role + "=" +
              given->second + ")");
  }
  const std::vector<std::string> found = file.present(spec.names);
  if (found.size() > 1) {
    file.fail("both '" + found[0] + "' and '" + found[1] + "' could be the " + spec.description + "; give --key " +
              role + "=NAME");
  }
  if (found.empty()) return std::nullopt;
  return found.front();
}

std::string requireRoleKey(const ForeignStorage& file, const OpenCvCalibrationOptions& options,
                           const std::string& role) {
  if (auto key = findRoleKey(file, options, role)) return *key;
  const RoleSpec& spec = roleSpec(role);
  const bool distortion = role == "camera_distortion" || role == "projector_distortion";
  file.fail("no " + spec.description + " (tried " + joined(spec.names) + "; give --key " + role + "=NAME" +
            (distortion ? ", or =none for a lens without distortion)" : ")"));
}

// --- image sizes -------------------------------------------------------------------------------

struct ImageSize {
  int width = 0, height = 0;
  std::string source;  // the key(s) it came from
  bool operator!=(const ImageSize& other) const { return width != other.width || height != other.height; }
  std::string text() const { return std::to_string(width) + "x" + std::to_string(height); }
};

// Where a device's image size may be stored: OpenCV's cv::Size is (width, height), numpy's shape
// is (rows, cols[, channels]); the key's name tells which.
struct SizeKeys {
  std::vector<std::pair<std::string, std::string>> width_and_height;
  std::vector<std::string> width_first;
  std::vector<std::string> height_first;
};

const SizeKeys& cameraSizeKeys() {
  static const SizeKeys keys = {
      {{"camera_width", "camera_height"},
       {"cam_width", "cam_height"},
       {"image_width", "image_height"},
       {"img_width", "img_height"}},
      {"camera_size", "cam_size", "image_size", "imageSize", "img_size", "imgSize", "camera_resolution"},
      {"img_shape", "image_shape", "cam_shape", "camera_shape"}};
  return keys;
}

const SizeKeys& projectorSizeKeys() {
  static const SizeKeys keys = {{{"projector_width", "projector_height"}, {"proj_width", "proj_height"}},
                                {"projector_size", "proj_size", "projectorSize", "projector_resolution"},
                                {"proj_shape", "projector_shape"}};
  return keys;
}

std::vector<std::string> allSizeKeys(const SizeKeys& keys) {
  std::vector<std::string> names;
  for (const auto& [width, height] : keys.width_and_height) names.push_back(width + "/" + height);
  names.insert(names.end(), keys.width_first.begin(), keys.width_first.end());
  names.insert(names.end(), keys.height_first.begin(), keys.height_first.end());
  return names;
}

int pixelCount(const ForeignStorage& file, const std::string& key, double value) {
  if (!(value >= 1.0 && value <= 65536.0 && value == std::floor(value))) {
    file.fail("'" + key + "' must hold whole numbers of pixels in [1, 65536] (got " + std::to_string(value) + ")");
  }
  return static_cast<int>(value);
}

ImageSize sizeFromPair(const ForeignStorage& file, const std::string& width_key, const std::string& height_key) {
  const StoredNumbers width = file.numbers(width_key), height = file.numbers(height_key);
  if (width.values.size() != 1) file.fail("'" + width_key + "' must be one number");
  if (height.values.size() != 1) file.fail("'" + height_key + "' must be one number");
  return {pixelCount(file, width_key, width.values[0]), pixelCount(file, height_key, height.values[0]),
          width_key + "/" + height_key};
}

// `height_first`: numpy's (rows, cols), optionally followed by the channel count.
ImageSize sizeFromVector(const ForeignStorage& file, const std::string& key, bool height_first) {
  const StoredNumbers stored = file.numbers(key);
  const std::size_t count = stored.values.size();
  if (count != 2 && !(height_first && count == 3)) {
    file.fail("'" + key + "' must hold " + (height_first ? "rows and cols" : "width and height") + " (got " +
              stored.shapeText() + " values)");
  }
  const int first = pixelCount(file, key, stored.values[0]), second = pixelCount(file, key, stored.values[1]);
  return height_first ? ImageSize{second, first, key} : ImageSize{first, second, key};
}

// Every size the file stores for the device; they must agree.
std::optional<ImageSize> sizeInFile(const ForeignStorage& file, const SizeKeys& keys, const std::string& device) {
  std::vector<ImageSize> sizes;
  for (const auto& [width, height] : keys.width_and_height) {
    if (file.has(width) || file.has(height)) sizes.push_back(sizeFromPair(file, width, height));
  }
  for (const std::string& key : file.present(keys.width_first)) sizes.push_back(sizeFromVector(file, key, false));
  for (const std::string& key : file.present(keys.height_first)) sizes.push_back(sizeFromVector(file, key, true));
  for (const ImageSize& size : sizes) {
    if (size != sizes.front()) {
      file.fail("the " + device + " image size is " + sizes.front().text() + " by '" + sizes.front().source + "' but " +
                size.text() + " by '" + size.source + "'");
    }
  }
  if (sizes.empty()) return std::nullopt;
  return sizes.front();
}

// The size given in the options (width, height > 0) or stored in the file. `option` names the
// command-line option that gives it, for the error when neither has it.
ImageSize deviceSize(const ForeignStorage& file, const SizeKeys& keys, const std::string& device, int width, int height,
                     const std::string& option) {
  const std::optional<ImageSize> stored = sizeInFile(file, keys, device);
  const ImageSize given{width, height, option};
  if (width > 0 && stored && *stored != given) {
    file.fail("the " + device + " image is " + stored->text() + " by '" + stored->source + "' but " + given.text() +
              " by " + option + ": the " + device + " matrix belongs to the file's size");
  }
  if (width > 0) return given;
  if (stored) return *stored;
  file.fail("no " + device + " image size (tried " + joined(allSizeKeys(keys)) + "; give " + option + " WxH)");
}

// --- lenses ------------------------------------------------------------------------------------

bool nearZero(double value, double scale) { return std::abs(value) <= 1e-9 * std::max(1.0, std::abs(scale)); }

// [fx 0 cx; 0 fy cy; 0 0 1]; MATLAB's IntrinsicMatrix is its transpose, which the error names.
void readCameraMatrix(const ForeignStorage& file, const std::string& key, const std::string& device,
                      LensIntrinsics& lens) {
  const StoredNumbers stored = file.numbers(key);
  if (stored.shape != std::vector<int>{3, 3} && stored.shape != std::vector<int>{9}) {
    file.fail("the " + device + " matrix '" + key + "' must be 3x3 (got " + stored.shapeText() + ")");
  }
  const auto k = [&](int row, int col) { return stored.values[3 * row + col]; };
  const bool transposed = k(0, 2) == 0.0 && k(1, 2) == 0.0 && (k(2, 0) != 0.0 || k(2, 1) != 0.0);
  if (transposed) file.fail("the " + device + " matrix '" + key + "' is transposed ([fx 0 0; 0 fy 0; cx cy 1])");
  if (!nearZero(k(0, 1), k(0, 0))) file.fail("the " + device + " matrix '" + key + "' has skew (lens model: none)");
  if (k(1, 0) != 0.0 || k(2, 0) != 0.0 || k(2, 1) != 0.0 || k(2, 2) != 1.0) {
    file.fail("the " + device + " matrix '" + key + "' must be [fx 0 cx; 0 fy cy; 0 0 1]");
  }
  lens.fx = k(0, 0);
  lens.fy = k(1, 1);
  lens.cx = k(0, 2);
  lens.cy = k(1, 2);
}

// OpenCV's order of distortion coefficients, of which the lens model (lens.hpp) has the first 5.
const char* const kDistortionNames[] = {"k1", "k2", "p1", "p2", "k3", "k4",   "k5",
                                        "k6", "s1", "s2", "s3", "s4", "tauX", "tauY"};

std::array<double, 5> readDistortion(const ForeignStorage& file, const std::string& key, const std::string& device) {
  std::array<double, 5> distortion{};
  if (key == kNoDistortion) return distortion;
  const StoredNumbers stored = file.numbers(key);
  const std::size_t count = stored.values.size();
  const bool vector =
      stored.shape.size() == 1 || (stored.shape.size() == 2 && std::min(stored.shape[0], stored.shape[1]) == 1);
  if (!vector || (count != 4 && count != 5 && count != 8 && count != 12 && count != 14)) {
    file.fail("the " + device + " distortion '" + key + "' must hold 4, 5, 8, 12 or 14 coefficients (got " +
              stored.shapeText() + ")");
  }
  std::string unsupported;
  for (std::size_t i = 0; i < count; ++i) {
    if (i < distortion.size()) {
      distortion[i] = stored.values[i];
    } else if (stored.values[i] != 0.0) {
      unsupported += (unsupported.empty() ? "" : ", ") + std::string(kDistortionNames[i]) + " = " +
                     std::to_string(stored.values[i]);
    }
  }
  if (!unsupported.empty()) {
    file.fail("the " + device + " distortion '" + key + "' has " + unsupported +
              ": the lens model has k1 k2 p1 p2 k3 only (calibrate without the rational, thin-prism and tilted "
              "models)");
  }
  return distortion;
}

LensIntrinsics readLens(const ForeignStorage& file, const OpenCvCalibrationOptions& options, const std::string& device,
                        const ImageSize& size) {
  LensIntrinsics lens;
  lens.width = size.width;
  lens.height = size.height;
  readCameraMatrix(file, requireRoleKey(file, options, device + "_matrix"), device, lens);
  lens.distortion = readDistortion(file, requireRoleKey(file, options, device + "_distortion"), device);
  try {
    lens.validate(device);
  } catch (const core::Error& e) {
    file.fail(e.what());
  }
  return lens;
}

// --- the projector's pose ----------------------------------------------------------------------

double metresPerUnit(LengthUnit units) { return units == LengthUnit::Millimetres ? 1e-3 : 1.0; }

// Reads `role`'s numbers through `interpret`, naming the key in its errors.
template <class Interpret>
auto interpreted(const ForeignStorage& file, const std::string& key, const std::string& role, Interpret interpret) {
  try {
    return interpret(file.numbers(key));
  } catch (const core::Error& e) {
    const std::string message = e.what();
    if (message.rfind(file.path() + ": ", 0) == 0) throw;  // already names the file
    file.fail("the " + roleSpec(role).description + " '" + key + "' " + message);
  }
}

detail::BoardViews boardViews(const ForeignStorage& file, const OpenCvCalibrationOptions& options,
                              const std::string& device, double metres_per_unit) {
  const std::string rotation_role = device + "_board_rotation", translation_role = device + "_board_translation";
  detail::BoardViews views;
  views.rotations = interpreted(file, requireRoleKey(file, options, rotation_role), rotation_role, detail::rotationsOf);
  views.translations =
      interpreted(file, requireRoleKey(file, options, translation_role), translation_role, detail::translationsOf);
  for (Eigen::Vector3d& t : views.translations) t *= metres_per_unit;
  return views;
}

// R and T, or where neither is stored, the composition of both devices' board poses.
Eigen::Isometry3d projectorPose(const ForeignStorage& file, const OpenCvCalibrationOptions& options) {
  const double metres_per_unit = metresPerUnit(options.units);
  const std::optional<std::string> rotation = findRoleKey(file, options, "rotation");
  const std::optional<std::string> translation = findRoleKey(file, options, "translation");
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  if (rotation || translation) {
    pose.linear() = interpreted(file, requireRoleKey(file, options, "rotation"), "rotation", detail::rotationOf);
    pose.translation() = metres_per_unit * interpreted(file, requireRoleKey(file, options, "translation"),
                                                       "translation", detail::translationOf);
    return pose;
  }
  const bool has_board_poses = findRoleKey(file, options, "camera_board_rotation").has_value();
  if (!has_board_poses) requireRoleKey(file, options, "rotation");  // the error names what was tried
  try {
    return detail::composeFromBoardViews(boardViews(file, options, "camera", metres_per_unit),
                                         boardViews(file, options, "projector", metres_per_unit));
  } catch (const core::Error& e) {
    const std::string message = e.what();
    if (message.rfind(file.path() + ": ", 0) == 0) throw;
    file.fail(message);
  }
}

// A baseline read in the wrong unit is a thousand times off; no structured-light rig has one
// under a millimetre or over ten metres.
void checkBaselineUnit(const ForeignStorage& file, const Eigen::Vector3d& translation, LengthUnit units) {
  const double baseline = translation.norm();
  char text[200];
  if (units == LengthUnit::Millimetres && baseline < 1e-3) {
    std::snprintf(text, sizeof text, "the baseline is %.4g mm read as millimetres: is the file in metres (--units m)?",
                  baseline * 1e3);
    file.fail(text);
  }
  if (units == LengthUnit::Metres && baseline > 10.0) {
    std::snprintf(text, sizeof text, "the baseline is %.4g m read as metres: is the file in millimetres (--units mm)?",
                  baseline);
    file.fail(text);
  }
}

}  // namespace

LengthUnit lengthUnitFromName(const std::string& name) {
  if (name == "mm") return LengthUnit::Millimetres;
  if (name == "m") return LengthUnit::Metres;
  throw core::Error("unknown length unit '" + name + "' (mm or m)");
}

const std::vector<std::string>& openCvCalibrationRoles() {
  static const std::vector<std::string> roles = [] {
    std::vector<std::string> names;
    for (const RoleSpec& spec : roleSpecs()) names.push_back(spec.role);
    return names;
  }();
  return roles;
}

const std::vector<std::string>& openCvCalibrationKeyNames(const std::string& role) { return roleSpec(role).names; }

void OpenCvCalibrationOptions::validate() const {
  const auto requireSize = [](int width, int height, const char* field) {
    core::requireField(width >= 0 && height >= 0 && (width > 0) == (height > 0) && width <= 65536 && height <= 65536,
                       "OpenCvCalibrationOptions", field, "both 0 or both in [1, 65536]",
                       std::to_string(width) + "x" + std::to_string(height));
  };
  requireSize(camera_width, camera_height, "camera_width/camera_height");
  requireSize(projector_width, projector_height, "projector_width/projector_height");
  for (const auto& [role, key] : keys) {
    roleSpec(role);
    if (key.empty()) throw core::Error("the key given for calibration role '" + role + "' is empty");
    const bool distortion = role == "camera_distortion" || role == "projector_distortion";
    if (key == kNoDistortion && !distortion) {
      throw core::Error(
          "'none' is a key only for camera_distortion and projector_distortion (a lens without "
          "distortion), not for " +
          role);
    }
  }
}

RigCalibration readOpenCvCalibration(const std::string& path, const OpenCvCalibrationOptions& options) {
  options.validate();
  const ForeignStorage file(path);
  RigCalibration rig;
  try {
    const ImageSize camera_size =
        deviceSize(file, cameraSizeKeys(), "camera", options.camera_width, options.camera_height, "--camera");
    const ImageSize projector_size = deviceSize(file, projectorSizeKeys(), "projector", options.projector_width,
                                                options.projector_height, "--projector");
    rig.camera = readLens(file, options, "camera", camera_size);
    rig.projector = readLens(file, options, "projector", projector_size);
    rig.T_projector_camera = projectorPose(file, options);
  } catch (const cv::Exception& e) {
    file.fail("malformed OpenCV FileStorage content: " + e.err);
  }
  checkBaselineUnit(file, rig.T_projector_camera.translation(), options.units);
  try {
    rig.validate();
  } catch (const core::Error& e) {
    file.fail(e.what());
  }
  return rig;
}

}  // namespace binpick::io
