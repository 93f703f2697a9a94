// Poses on the wire, shared by requests (POSE) and replies (NEXT) of both framings: millimetres
// and the orientation convention's values, as text or as int32 fixed point; fixed-point quaternions
// that point as close as their resolution allows.
#include <charconv>
#include <cmath>

#include "binpick/core/error.hpp"
#include "codec.hpp"

namespace binpick::robot::detail {

namespace {

// Fixed-point text of `value`, nothing if it could not fit any line. to_chars: no locale.
std::optional<std::string> fixedText(double value, int decimals) {
  if (!(std::abs(value) < 1e15)) return std::nullopt;
  std::array<char, 64> buffer{};
  const auto result =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, std::chars_format::fixed, decimals);
  if (result.ec != std::errc()) return std::nullopt;
  std::string text(buffer.data(), result.ptr);
  // "-0.00" (a tiny negative rounded to zero) would read as a sign the value does not have.
  if (text.front() == '-' && text.find_first_not_of("-0.") == std::string::npos) text.erase(0, 1);
  return text;
}

// The orientation values of R, a quaternion already on the grid of `unitsPerValue` (see
// roundQuaternion): rounding its components one by one would point it less well.
std::vector<double> gridOrientationValues(const Eigen::Matrix3d& R, core::Orientation orientation,
                                          double unitsPerValue) {
  std::vector<double> values = core::orientationValues(R, orientation);
  if (orientation != core::Orientation::Quaternion) return values;
  const std::array<double, 4> units = roundQuaternion(values, unitsPerValue);
  for (std::size_t k = 0; k < 4; ++k) values[k] = units[k] / unitsPerValue;
  return values;
}

}  // namespace

std::optional<Eigen::Isometry3d> poseFromWireValues(const std::vector<double>& values, core::Orientation orientation,
                                                    std::string& problem) {
  const std::size_t expected = 3 + static_cast<std::size_t>(core::orientationValueCount(orientation));
  if (values.size() != expected) {
    problem = "a pose is x, y, z and " + std::to_string(expected - 3) + " " + core::orientationName(orientation) +
              " values (got " + std::to_string(values.size()) + " numbers)";
    return std::nullopt;
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(values[0], values[1], values[2]) / kMillimetresPerMetre;
  try {
    T.linear() = core::rotationFromValues({values.begin() + 3, values.end()}, orientation);
  } catch (const core::Error& error) {
    problem = error.what();
    return std::nullopt;
  }
  return T;
}

std::optional<double> parseFiniteNumber(std::string_view text) {
  double value = 0.0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || result.ec != std::errc() || result.ptr != text.data() + text.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

std::optional<std::string> asciiPoseText(const Eigen::Isometry3d& T, core::Orientation orientation,
                                         int positionDecimals, int orientationDecimals) {
  std::string text;
  const Eigen::Vector3d millimetres = T.translation() * kMillimetresPerMetre;
  for (int axis = 0; axis < 3; ++axis) {
    const std::optional<std::string> number = fixedText(millimetres[axis], positionDecimals);
    if (!number) return std::nullopt;
    text += "," + *number;
  }
  const double unitsPerValue = std::pow(10.0, orientationDecimals);
  for (double value : gridOrientationValues(T.linear(), orientation, unitsPerValue)) {
    const std::optional<std::string> number = fixedText(value, orientationDecimals);
    if (!number) return std::nullopt;
    text += "," + *number;
  }
  return text;
}

std::optional<BinaryPoseFields> binaryPoseFields(const Eigen::Isometry3d& T, const CodecParams& params) {
  BinaryPoseFields fields{};  // x, y, z, then up to 4 orientation values, unused 0
  const Eigen::Vector3d millimetres = T.translation() * kMillimetresPerMetre;
  for (int axis = 0; axis < 3; ++axis) {
    const std::optional<int32_t> field = fixedPoint(millimetres[axis], params.position_scale);
    if (!field) return std::nullopt;
    fields[static_cast<std::size_t>(axis)] = *field;
  }
  const std::vector<double> values = gridOrientationValues(T.linear(), params.orientation, params.orientation_scale);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::optional<int32_t> field = fixedPoint(values[i], params.orientation_scale);
    if (!field) return std::nullopt;
    fields[3 + i] = *field;
  }
  return fields;
}

std::optional<Eigen::Isometry3d> poseFromBinaryFields(const BinaryPoseFields& fields, const CodecParams& params,
                                                      std::string& problem) {
  const std::size_t count = static_cast<std::size_t>(core::orientationValueCount(params.orientation));
  for (std::size_t i = 3 + count; i < kBinaryPoseFields; ++i) {
    if (fields[i] != 0) {
      problem = "an unused orientation field is not 0";
      return std::nullopt;
    }
  }
  std::vector<double> values;
  for (std::size_t axis = 0; axis < 3; ++axis) values.push_back(fields[axis] / params.position_scale);
  for (std::size_t i = 0; i < count; ++i) values.push_back(fields[3 + i] / params.orientation_scale);
  return poseFromWireValues(values, params.orientation, problem);
}

namespace {

// The angle between the rotations of unit q and of nonzero p, up to a monotonic function: the
// part of p across q relative to the part along it.
double misalignment(const Eigen::Vector4d& p, const Eigen::Vector4d& q) {
  const double along = p.dot(q);
  return (p - along * q).squaredNorm() / (along * along);
}

}  // namespace

std::array<double, 4> roundQuaternion(const std::vector<double>& q, double unitsPerValue) {
  const Eigen::Vector4d unit(q[0], q[1], q[2], q[3]);
  const Eigen::Vector4d scaled = unit * unitsPerValue;
  Eigen::Vector4d floor;
  for (int k = 0; k < 4; ++k) floor[k] = std::floor(scaled[k]);
  Eigen::Vector4d best = scaled.array().round();
  double bestMisalignment = misalignment(best, unit);
  for (int corner = 0; corner < 16; ++corner) {
    Eigen::Vector4d candidate = floor;
    for (int k = 0; k < 4; ++k) candidate[k] += (corner >> k) & 1;
    const double candidateMisalignment = misalignment(candidate, unit);
    if (candidateMisalignment < bestMisalignment) {
      best = candidate;
      bestMisalignment = candidateMisalignment;
    }
  }
  return {best[0], best[1], best[2], best[3]};
}

}  // namespace binpick::robot::detail
