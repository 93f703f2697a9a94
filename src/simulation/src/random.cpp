#include "random.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace binpick::simulation::detail {
namespace {
constexpr double kTwoPi = 6.28318530717958647692;
constexpr uint64_t kGoldenGamma = 0x9E3779B97F4A7C15ULL;  // SplitMix64's counter step
}  // namespace

Rng makeRng(uint64_t seed, uint32_t stream) {
  // std::seed_seq's mixing is specified by the standard, unlike the distributions.
  std::seed_seq sequence{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32), stream};
  return Rng(sequence);
}

double uniform01(Rng& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

double uniform(Rng& rng, double low, double high) { return low + (high - low) * uniform01(rng); }

uint64_t SplitMix64::operator()() {
  uint64_t z = (state_ += kGoldenGamma);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

KeyedStreams::KeyedStreams(uint64_t seed, uint32_t stream) {
  // Hash the seed, then the stream, so that no two (seed, stream) pairs share a starting point.
  SplitMix64 seed_hash(seed);
  SplitMix64 stream_hash(seed_hash() + stream);
  base_ = stream_hash();
}

SplitMix64 KeyedStreams::forItem(uint64_t index) const {
  return SplitMix64(base_ + kDrawsPerItem * index * kGoldenGamma);
}

double uniform01(SplitMix64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

double standardNormal(SplitMix64& rng) {
  const double radius = std::sqrt(-2.0 * std::log(1.0 - uniform01(rng)));  // 1 - u in (0, 1]
  return radius * std::cos(kTwoPi * uniform01(rng));
}

Eigen::Matrix3d uniformRotation(Rng& rng) {
  const double u1 = uniform01(rng), u2 = uniform01(rng), u3 = uniform01(rng);
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const Eigen::Quaterniond q(b * std::cos(kTwoPi * u3), a * std::sin(kTwoPi * u2), a * std::cos(kTwoPi * u2),
                             b * std::sin(kTwoPi * u3));
  return q.normalized().toRotationMatrix();
}

}  // namespace binpick::simulation::detail
