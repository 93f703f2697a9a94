#pragma once
// Typed reading and writing of the project's JSON files (capture metadata, truth files, detection
// results): every key required and type-checked, messages "PATH: ..." naming the key. Pure
// functions: thread-safe.
#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <type_traits>

#include "binpick/core/error.hpp"

namespace binpick::core {

// The whole file parsed. Throws "PATH: cannot open ..." or "PATH: malformed JSON: ...".
nlohmann::json readJsonFile(const std::string& path);

namespace json_detail {

// JSON numbers convert silently (64.5 to 64, true to 1, 2^32 + 64 to 64): only exact fits pass.
template <typename T>
bool holdsExactly(const nlohmann::json& value) {
  if constexpr (std::is_same_v<T, int>) {
    if (value.is_number_unsigned()) {
      return value.get<std::uint64_t>() <= static_cast<std::uint64_t>(std::numeric_limits<int>::max());
    }
    if (!value.is_number_integer()) return false;
    const std::int64_t v = value.get<std::int64_t>();
    return v >= std::numeric_limits<int>::min() && v <= std::numeric_limits<int>::max();
  } else if constexpr (std::is_same_v<T, double>) {
    return value.is_number();
  } else {
    return true;  // strings, booleans, arrays and objects: get<T> checks the type itself
  }
}

}  // namespace json_detail

// The value at `key` of `object`, as a T. Throws "PATH: missing key 'KEY'" or "PATH: key 'KEY'
// has the wrong type" (also for a number that does not fit T exactly).
template <typename T>
T jsonField(const nlohmann::json& object, const char* key, const std::string& path) {
  if (!object.is_object()) {
    throw Error(path + ": expected an object holding '" + key + "'");
  }
  const auto it = object.find(key);
  if (it == object.end()) throw Error(path + ": missing key '" + key + "'");
  try {
    if (json_detail::holdsExactly<T>(*it)) return it->get<T>();
  } catch (const nlohmann::json::exception&) {
  }
  throw Error(path + ": key '" + key + "' has the wrong type");
}

// A pose as 4 rows of 4 numbers, in the scalar type it has (floats stay floats in the text).
template <typename Scalar>
nlohmann::json poseRows(const Eigen::Transform<Scalar, 3, Eigen::Isometry>& pose) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) {
    rows.push_back({pose(r, 0), pose(r, 1), pose(r, 2), pose(r, 3)});
  }
  return rows;
}

// The inverse of poseRows. Throws "PATH: 'WHAT' must be 4 rows of 4 numbers" or "PATH: 'WHAT' is
// not a finite rigid transform" (rotation orthonormal to 1e-5).
Eigen::Isometry3d poseFromRows(const nlohmann::json& rows, const std::string& path, const std::string& what);

}  // namespace binpick::core
