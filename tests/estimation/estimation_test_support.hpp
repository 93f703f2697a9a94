#pragma once
// Shared helpers of the estimation tests: cached prepared models, random poses, pose errors.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <string>
#include <utility>

#include "binpick/core/error.hpp"
#include "binpick/estimation/model.hpp"
#include "binpick/simulation/parts.hpp"
#include "thrown_message.hpp"

namespace binpick::estimation::testing {

constexpr double kPi = 3.14159265358979323846;
inline double deg(double radians) { return radians * 180.0 / kPi; }
inline float rad(float degrees) { return degrees * static_cast<float>(kPi / 180.0); }

// Angle between two rotations, degrees.
inline double rotationErrorDeg(const Eigen::Matrix3f& a, const Eigen::Matrix3f& b) {
  const Eigen::Matrix3d r = a.cast<double>().transpose() * b.cast<double>();
  const double c = std::clamp((r.trace() - 1.0) * 0.5, -1.0, 1.0);
  return deg(std::acos(c));
}
inline double translationError(const Eigen::Isometry3f& a, const Eigen::Isometry3f& b) {
  return (a.translation().cast<double>() - b.translation().cast<double>()).norm();
}

inline Eigen::Vector3f randomUnit(std::mt19937_64& rng) {
  std::normal_distribution<float> normal(0.0f, 1.0f);
  Eigen::Vector3f v;
  do {
    v = Eigen::Vector3f(normal(rng), normal(rng), normal(rng));
  } while (v.norm() < 1e-3f);
  return v.normalized();
}

// A rotation drawn uniformly and a translation in [-range, range]^3.
inline Eigen::Isometry3f randomPose(std::mt19937_64& rng, float range) {
  std::uniform_real_distribution<float> uniform(-range, range);
  Eigen::Quaternionf q;
  std::normal_distribution<float> normal(0.0f, 1.0f);
  q.coeffs() << normal(rng), normal(rng), normal(rng), normal(rng);
  q.normalize();
  Eigen::Isometry3f T = Eigen::Isometry3f::Identity();
  T.linear() = q.toRotationMatrix();
  T.translation() = Eigen::Vector3f(uniform(rng), uniform(rng), uniform(rng));
  return T;
}

// A pose `translation` away along a random direction and turned by `angle_deg` about a random
// axis through the model origin.
inline Eigen::Isometry3f perturbed(const Eigen::Isometry3f& pose, std::mt19937_64& rng, float translation,
                                   float angle_deg) {
  Eigen::Isometry3f delta = Eigen::Isometry3f::Identity();
  delta.linear() = Eigen::AngleAxisf(rad(angle_deg), randomUnit(rng)).toRotationMatrix();
  Eigen::Isometry3f result = pose * delta;
  result.translation() += translation * randomUnit(rng);
  return result;
}

// Prepared models are the slowest fixtures: build each (part, sampling ratio) once per process.
inline const PreparedModel& cachedModel(const std::string& part, float sampling_ratio = 0.04f) {
  static std::map<std::pair<std::string, float>, PreparedModel> models;
  const auto key = std::make_pair(part, sampling_ratio);
  auto it = models.find(key);
  if (it == models.end()) {
    ModelParams params;
    params.sampling_ratio = sampling_ratio;
    it = models.emplace(key, prepareModel(io::ModelGeometry{simulation::makePart(part).mesh, {}}, params)).first;
  }
  return it->second;
}

// A small clamp model (a few hundred points) for the tests that compare against brute force.
inline const PreparedModel& smallModel() { return cachedModel("clamp", 0.08f); }

// Runs `f`, expects core::Error and returns its message ("" and a failure when nothing or
// something else was thrown).
template <class F>
std::string errorMessage(F&& f) {
  std::string message;
  try {
    message = binpick::test::thrownMessage(f);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw a non-binpick exception: " << e.what();
    return "";
  }
  if (message.empty()) ADD_FAILURE() << "did not throw";
  return message;
}

}  // namespace binpick::estimation::testing
