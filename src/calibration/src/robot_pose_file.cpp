// poses.txt: reading with an error per line that names the view, and writing.
#include "binpick/calibration/robot_pose_file.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "binpick/core/error.hpp"
#include "binpick/core/file.hpp"

namespace binpick::calibration {
namespace {

std::vector<std::string> tokens(const std::string& line) {
  std::istringstream stream(line);
  std::vector<std::string> out;
  for (std::string token; stream >> token;) out.push_back(token);
  return out;
}

bool isViewName(const std::string& name) {
  for (const char c : name) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-';
    if (!ok) return false;
  }
  return !name.empty();
}

// Reports "ORIGIN:LINE: ..." for the line being read.
struct LineContext {
  const std::string& origin;
  int line = 0;
  [[noreturn]] void fail(const std::string& why) const {
    throw core::Error(origin + ":" + std::to_string(line) + ": " + why);
  }
};

double finiteNumber(const std::string& token, const std::string& view, const LineContext& at) {
  double value = 0.0;
  const char* end = token.data() + token.size();
  const auto [next, error] = std::from_chars(token.data(), end, value);
  if (error != std::errc() || next != end || !std::isfinite(value)) {
    at.fail("view " + view + ": '" + token + "' is not a finite number");
  }
  return value;
}

core::Orientation orientationLine(const std::string& line, const LineContext& at) {
  const auto colon = line.find(':');
  const std::vector<std::string> key = tokens(line.substr(0, colon));
  const std::vector<std::string> value =
      colon == std::string::npos ? std::vector<std::string>{} : tokens(line.substr(colon + 1));
  if (key.size() != 1 || key[0] != "orientation" || value.size() != 1) {
    at.fail("the first line must be 'orientation: NAME' (got '" + line + "')");
  }
  try {
    return core::orientationFromName(value[0]);
  } catch (const core::Error& e) {
    at.fail(e.what());
  }
}

// Values the conversion would silently normalise or wrap, which more likely mean another
// convention than a rotation: a quaternion whose norm is off 1, a rotation vector longer than pi
// (its reading is unique only up to pi; degrees written as radians give such lengths).
constexpr double kQuaternionNormTolerance = 0.01;
constexpr double kPi = 3.14159265358979323846;
constexpr double kRotationVectorSlack = 1e-4;  // radians: a controller rounding at pi

void requireRotationReading(const std::vector<double>& v, core::Orientation orientation, const std::string& view,
                            const LineContext& at) {
  char text[300];
  if (orientation == core::Orientation::Quaternion) {
    const double norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
    if (norm > 0.0 && std::abs(norm - 1.0) > kQuaternionNormTolerance) {
      std::snprintf(text, sizeof text,
                    "view %s: quaternion has norm %.4g; not a rotation (a unit quaternion w x y z has norm 1): "
                    "a different convention?",
                    view.c_str(), norm);
      at.fail(text);
    }
  }
  if (orientation == core::Orientation::RotationVector) {
    const double norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (norm > kPi + kRotationVectorSlack) {
      std::snprintf(text, sizeof text,
                    "view %s: rotation vector of length %.4g rad is longer than pi: a rotation vector (rx ry rz, "
                    "radians) is read uniquely only up to pi; degrees, or a different convention?",
                    view.c_str(), norm);
      at.fail(text);
    }
  }
}

RobotPose poseLine(const std::vector<std::string>& fields, core::Orientation orientation, const LineContext& at) {
  RobotPose pose;
  pose.view = fields[0];
  pose.line = at.line;
  if (!isViewName(pose.view)) at.fail("'" + pose.view + "' is not a view name ([A-Za-z0-9_.-]+)");
  const int count = core::orientationValueCount(orientation);
  if (static_cast<int>(fields.size()) != 4 + count) {
    at.fail("view " + pose.view + ": expected x y z (mm) and " + std::to_string(count) + " " +
            core::orientationName(orientation) + " values, got " + std::to_string(fields.size() - 1) + " numbers");
  }
  std::vector<double> values;
  for (std::size_t i = 1; i < fields.size(); ++i) values.push_back(finiteNumber(fields[i], pose.view, at));
  pose.T_base_flange.translation() = Eigen::Vector3d(values[0], values[1], values[2]) / 1000.0;
  requireRotationReading({values.begin() + 3, values.end()}, orientation, pose.view, at);
  try {
    pose.T_base_flange.linear() = core::rotationFromValues({values.begin() + 3, values.end()}, orientation);
  } catch (const core::Error& e) {
    at.fail("view " + pose.view + ": " + e.what());
  }
  return pose;
}

void appendFixed(std::string& text, double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, " %.*f", decimals, value);
  text += buffer;
}

}  // namespace

RobotPoseFile parseRobotPoses(const std::string& text, const std::string& origin) {
  RobotPoseFile file;
  bool have_orientation = false;
  std::map<std::string, int> first_line;  // view -> line, to name both places of a duplicate
  std::istringstream lines(text);
  LineContext at{origin};
  for (std::string line; std::getline(lines, line);) {
    ++at.line;
    const std::vector<std::string> fields = tokens(line);
    if (fields.empty() || fields[0][0] == '#') continue;
    if (!have_orientation) {
      file.orientation = orientationLine(line, at);
      have_orientation = true;
      continue;
    }
    RobotPose pose = poseLine(fields, file.orientation, at);
    const auto [seen, inserted] = first_line.emplace(pose.view, at.line);
    if (!inserted) {
      at.fail("view " + pose.view + " is listed twice (first on line " + std::to_string(seen->second) + ")");
    }
    file.poses.push_back(std::move(pose));
  }
  if (!have_orientation) throw core::Error(origin + ": no 'orientation: NAME' line");
  return file;
}

RobotPoseFile readRobotPoseFile(const std::string& path) { return parseRobotPoses(core::readFile(path), path); }

std::string formatRobotPoses(const RobotPoseFile& file) {
  std::string text =
      "# Robot poses T_base_flange (flange in the base frame), one per view: VIEW x y z (mm) and"
      " the rotation\norientation: " +
      core::orientationName(file.orientation) + "\n";
  for (const RobotPose& pose : file.poses) {
    text += pose.view;
    for (int i = 0; i < 3; ++i) appendFixed(text, 1000.0 * pose.T_base_flange.translation()(i), 4);
    for (const double v : core::orientationValues(pose.T_base_flange.linear(), file.orientation)) {
      appendFixed(text, v, 9);
    }
    text += "\n";
  }
  return text;
}

void writeRobotPoseFile(const std::string& path, const RobotPoseFile& file) {
  core::writeFileAtomically(path, formatRobotPoses(file), core::ParentDirectory::Create);
}

}  // namespace binpick::calibration
