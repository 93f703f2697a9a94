#include "binpick/core/json_fields.hpp"

#include "binpick/core/file.hpp"

namespace binpick::core {
namespace {

bool isFourByFourNumbers(const nlohmann::json& rows) {
  if (!rows.is_array() || rows.size() != 4) return false;
  for (const nlohmann::json& row : rows) {
    if (!row.is_array() || row.size() != 4) return false;
    for (const nlohmann::json& value : row) {
      if (!value.is_number()) return false;
    }
  }
  return true;
}

}  // namespace

nlohmann::json readJsonFile(const std::string& path) {
  const std::string text = readFile(path);
  if (text.empty()) throw Error(path + ": the file is empty");
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": malformed JSON: " + e.what());
  }
}

Eigen::Isometry3d poseFromRows(const nlohmann::json& rows, const std::string& path, const std::string& what) {
  if (!isFourByFourNumbers(rows)) {
    throw Error(path + ": '" + what + "' must be 4 rows of 4 numbers");
  }
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) m(r, c) = rows[r][c].get<double>();
  }
  const Eigen::Matrix3d rotation = m.topLeftCorner<3, 3>();
  const bool rigid = m.allFinite() && (rotation * rotation.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-5 &&
                     m.row(3) == Eigen::RowVector4d(0, 0, 0, 1);
  if (!rigid) throw Error(path + ": '" + what + "' is not a finite rigid transform");
  Eigen::Isometry3d pose;
  pose.matrix() = m;
  return pose;
}

}  // namespace binpick::core
