#include "normal_table.hpp"

#include <array>
#include <cmath>
#include <memory>

namespace binpick::simulation::detail {
namespace {

constexpr int kTableBits = 16;
constexpr int kTableSize = 1 << kTableBits;

double standardNormalCdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

// Bisection: slow but simple and exact to double precision; runs once per process.
double standardNormalQuantile(double p) {
  double lo = -10.0, hi = 10.0;
  for (int i = 0; i < 64; ++i) {
    const double mid = 0.5 * (lo + hi);
    (standardNormalCdf(mid) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

using Table = std::array<float, kTableSize>;

std::unique_ptr<Table> makeTable() {
  auto table = std::make_unique<Table>();
  for (int k = 0; k < kTableSize; ++k) {
    (*table)[k] = static_cast<float>(standardNormalQuantile((k + 0.5) / kTableSize));
  }
  return table;
}

}  // namespace

double tabulatedStandardNormal(uint64_t bits) {
  // Built on first use; C++11 guarantees one thread builds it while the others wait.
  static const std::unique_ptr<Table> table = makeTable();
  return (*table)[bits >> (64 - kTableBits)];
}

}  // namespace binpick::simulation::detail
