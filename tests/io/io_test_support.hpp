#pragma once
// Shared helpers for the io tests: a fresh temporary directory per test, files written from text
// or bytes, byte builders for hand-made binary files, and an error-message assertion.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <ostream>
#include <string>
#include <type_traits>

#include "binpick/core/error.hpp"
#include "binpick/io/geometry_io.hpp"
#include "binpick/io/point_cloud.hpp"
#include "temp_directory_test.hpp"

namespace binpick {
// Readable parameter names in test output instead of "4-byte object <01-00 00-00>".
inline void PrintTo(io::Encoding encoding, std::ostream* out) {
  *out << (encoding == io::Encoding::Binary ? "Binary" : "Ascii");
}
}  // namespace binpick

namespace binpick::test {

// Each test gets its own directory (TempDirectoryTest), plus ways to fill it.
class IoTest : public TempDirectoryTest {
 protected:
  std::string writeFile(const std::string& name, const std::string& bytes) const {
    const std::string path = pathOf(name);
    std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return path;
  }

  static std::string readFile(const std::string& path) {
    std::ifstream stream(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(stream), {});
  }
};

// Appends `value` with the given byte order, for hand-made binary files.
template <typename T>
void appendBytes(std::string& out, T value, bool bigEndian = false) {
  static_assert(std::is_trivially_copyable_v<T>);
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  const bool hostIsBig = __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__;
  if (bigEndian != hostIsBig) std::reverse(bytes, bytes + sizeof(T));
  out.append(bytes, sizeof(T));
}

// Passes when `action` throws core::Error whose message starts with "PATH: " and contains
// `fragment`.
template <typename Action>
::testing::AssertionResult failsWith(Action&& action, const std::string& path, const std::string& fragment) {
  try {
    action();
  } catch (const core::Error& error) {
    const std::string message = error.what();
    if (message.rfind(path + ": ", 0) != 0) {
      return ::testing::AssertionFailure() << "message does not start with the path: " << message;
    }
    if (message.find(fragment) == std::string::npos) {
      return ::testing::AssertionFailure() << "message lacks '" << fragment << "': " << message;
    }
    return ::testing::AssertionSuccess();
  } catch (const std::exception& other) {
    return ::testing::AssertionFailure() << "threw a non-binpick exception: " << other.what();
  }
  return ::testing::AssertionFailure() << "did not throw; expected an error with '" << fragment << "'";
}

// Deterministic noise standing in for a corrupt file.
inline std::string garbageBytes(std::size_t size, std::uint32_t seed) {
  std::string bytes(size, '\0');
  for (char& byte : bytes) {
    seed = seed * 1664525u + 1013904223u;
    byte = static_cast<char>(seed >> 24);
  }
  return bytes;
}

inline bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

inline bool sameBits(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  return std::memcmp(a.data(), b.data(), sizeof(float) * 3) == 0;
}

// A small organized cloud (4 x 3) with unit normals and two invalid (NaN) pixels.
inline io::PointCloud organizedCloudWithHoles() {
  io::PointCloud cloud;
  cloud.width = 4;
  cloud.height = 3;
  for (int row = 0; row < cloud.height; ++row) {
    for (int column = 0; column < cloud.width; ++column) {
      cloud.points.emplace_back(0.001f * column - 0.123456789f, 0.002f * row + 1e-7f, 0.75f + 1e-3f * row * column);
      cloud.normals.push_back(Eigen::Vector3f(column - 1.5f, row + 0.25f, -3.0f).normalized());
    }
  }
  const float nan = std::numeric_limits<float>::quiet_NaN();
  cloud.points[5] = Eigen::Vector3f(nan, nan, nan);
  cloud.normals[5] = Eigen::Vector3f(nan, nan, nan);
  cloud.points[10] = Eigen::Vector3f(nan, nan, nan);
  cloud.normals[10] = Eigen::Vector3f(nan, nan, nan);
  return cloud;
}

// A NaN with a payload, so that tests can see whether its bits survive.
inline float nanWithPayload() {
  const std::uint32_t bits = 0x7fc01234u;
  float value;
  std::memcpy(&value, &bits, sizeof(value));
  return value;
}

// `cloud` with one intensity per point: values in (0, 1) without a short decimal form on valid
// points, and NaN (with a payload) on invalid pixels, as a sensor pipeline leaves them.
inline io::PointCloud withIntensities(io::PointCloud cloud) {
  cloud.intensities.resize(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    cloud.intensities[i] = cloud.points[i].allFinite() ? 1.0f / static_cast<float>(i + 3) : nanWithPayload();
  }
  return cloud;
}

// An unorganized cloud with awkward values: tiny, huge, negative zero, many digits.
inline io::PointCloud awkwardCloud() {
  io::PointCloud cloud;
  cloud.points = {Eigen::Vector3f(0.1f, -0.0f, 3.14159274f), Eigen::Vector3f(1e-30f, 1e30f, -7.0f),
                  Eigen::Vector3f(123456.789f, -0.000123f, 2.0f / 3.0f)};
  return cloud;
}

}  // namespace binpick::test
