#pragma once
// Seeded random numbers with results fixed by this code rather than by the standard library's
// distributions (whose algorithms differ between implementations), so a seed gives the same pile
// everywhere. Internal to binpick::simulation; each generator is owned by one caller.
#include <Eigen/Core>
#include <cstdint>
#include <random>

namespace binpick::simulation::detail {

using Rng = std::mt19937_64;

// An independent generator per purpose (placement, sensor noise, ...) so that changing how many
// numbers one stage draws does not shift the others.
Rng makeRng(uint64_t seed, uint32_t stream);

double uniform01(Rng& rng);                         // [0, 1), 53 random bits
double uniform(Rng& rng, double low, double high);  // [low, high)

// SplitMix64 (Steele, Lea, Flood 2014): a tiny generator whose state is a plain counter, so a
// stream can start anywhere at no cost. Used to key random numbers by pixel: the noise of pixel
// i is a function of (seed, i) only, whatever the order or thread that computes it.
class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t state) : state_(state) {}
  uint64_t operator()();

 private:
  uint64_t state_;
};

// Independent SplitMix64 generators for the items (pixels, ...) of one stream under one seed.
class KeyedStreams {
 public:
  KeyedStreams(uint64_t seed, uint32_t stream);
  // Item i's generator; it may draw up to kDrawsPerItem numbers without reaching item i + 1's.
  SplitMix64 forItem(uint64_t index) const;
  static constexpr uint64_t kDrawsPerItem = 4;

 private:
  uint64_t base_;
};

double uniform01(SplitMix64& rng);       // [0, 1), 53 random bits
double standardNormal(SplitMix64& rng);  // Box-Muller: one value from two uniforms

// A rotation drawn uniformly from SO(3) (Shoemake's random unit quaternion).
Eigen::Matrix3d uniformRotation(Rng& rng);

}  // namespace binpick::simulation::detail
