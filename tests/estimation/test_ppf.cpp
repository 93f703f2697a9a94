// Point pair features (eq. 1), their quantisation, the alpha bins and the local frames of eq. 2.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <utility>

#include "binpick/estimation/ppf.hpp"
#include "estimation_test_support.hpp"

namespace binpick::estimation {
namespace {

using testing::deg;
using testing::kPi;
using testing::rad;
using testing::randomPose;
using testing::randomUnit;

constexpr float kTwoPi = static_cast<float>(2.0 * kPi);
constexpr double kAngleTol = 1e-4;  // radians

PointPairFeature feature(float distance, float a1, float a2, float a3) {
  PointPairFeature f;
  f.distance = distance;
  f.angle_ni_d = a1;
  f.angle_nj_d = a2;
  f.angle_ni_nj = a3;
  return f;
}

TEST(PpfFeature, HandComputedValues) {
  // The example of the brief: d along +x, n1 along +z, n2 along +x.
  PointPairFeature f = computeFeature({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {1, 0, 0});
  EXPECT_NEAR(f.distance, 1.0, 1e-6);
  EXPECT_NEAR(deg(f.angle_ni_d), 90.0, 1e-4);
  EXPECT_NEAR(deg(f.angle_nj_d), 0.0, 1e-4);
  EXPECT_NEAR(deg(f.angle_ni_nj), 90.0, 1e-4);

  // Antiparallel normals along d: 0 and 180 degrees exactly (where an acos would lose accuracy).
  f = computeFeature({1, 2, 3}, {0, 1, 0}, {1, 4, 3}, {0, -1, 0});
  EXPECT_NEAR(f.distance, 2.0, 1e-6);
  EXPECT_NEAR(f.angle_ni_d, 0.0, kAngleTol);
  EXPECT_NEAR(f.angle_nj_d, kPi, kAngleTol);
  EXPECT_NEAR(f.angle_ni_nj, kPi, kAngleTol);

  // 45 degree cases: d = (3, 4, 0) (|d| = 5), n1 = (1, 1, 0)/sqrt2, n2 = (0, 0, 1).
  const float s = 1.0f / std::sqrt(2.0f);
  f = computeFeature({0, 0, 0}, {s, s, 0}, {3, 4, 0}, {0, 0, 1});
  EXPECT_NEAR(f.distance, 5.0, 1e-5);
  EXPECT_NEAR(f.angle_ni_d, std::acos((3.0 + 4.0) / (5.0 * std::sqrt(2.0))), kAngleTol);
  EXPECT_NEAR(deg(f.angle_nj_d), 90.0, 1e-3);
  EXPECT_NEAR(deg(f.angle_ni_nj), 90.0, 1e-3);

  // A tiny angle: n2 tilted 1e-3 rad from n1.
  f = computeFeature({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {std::sin(1e-3f), 0, std::cos(1e-3f)});
  EXPECT_NEAR(f.angle_ni_nj, 1e-3, 1e-6);
}

TEST(PpfFeature, SymmetryAndInvarianceProperties) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<float> coord(-0.1f, 0.1f);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3f pi(coord(rng), coord(rng), coord(rng)), pj(coord(rng), coord(rng), coord(rng));
    const Eigen::Vector3f ni = randomUnit(rng), nj = randomUnit(rng);
    const PointPairFeature f = computeFeature(pi, ni, pj, nj);
    for (float a : {f.angle_ni_d, f.angle_nj_d, f.angle_ni_nj}) {
      EXPECT_GE(a, 0.0f);
      EXPECT_LE(a, static_cast<float>(kPi));
    }
    // Swapping the points: d -> -d, so the two normal-to-d angles swap and become pi - angle.
    const PointPairFeature g = computeFeature(pj, nj, pi, ni);
    EXPECT_FLOAT_EQ(g.distance, f.distance);
    EXPECT_NEAR(g.angle_ni_d, kPi - f.angle_nj_d, kAngleTol);
    EXPECT_NEAR(g.angle_nj_d, kPi - f.angle_ni_d, kAngleTol);
    EXPECT_NEAR(g.angle_ni_nj, f.angle_ni_nj, kAngleTol);
    // Flipping both normals: the normal-to-d angles become pi - angle, the normal angle stays.
    const PointPairFeature h = computeFeature(pi, -ni, pj, -nj);
    EXPECT_NEAR(h.angle_ni_d, kPi - f.angle_ni_d, kAngleTol);
    EXPECT_NEAR(h.angle_nj_d, kPi - f.angle_nj_d, kAngleTol);
    EXPECT_NEAR(h.angle_ni_nj, f.angle_ni_nj, kAngleTol);
    // Invariant under rigid motions.
    const Eigen::Isometry3f T = randomPose(rng, 1.0f);
    const PointPairFeature r = computeFeature(T * pi, T.linear() * ni, T * pj, T.linear() * nj);
    EXPECT_NEAR(r.distance, f.distance, 1e-5);
    EXPECT_NEAR(r.angle_ni_d, f.angle_ni_d, kAngleTol);
    EXPECT_NEAR(r.angle_nj_d, f.angle_nj_d, kAngleTol);
    EXPECT_NEAR(r.angle_ni_nj, f.angle_ni_nj, kAngleTol);
  }
}

// Bins are compared through keys: a value lies in bin k when its key equals the key of the
// feature at the centre of bin k (all other components fixed).
class QuantizerEdges : public ::testing::Test {
 protected:
  // Dyadic steps: k * step is exact in float, so "exactly at k * step" is meaningful.
  PpfQuantizer q{0.25f, static_cast<float>(kPi / 16.0), 4.0f};
  int64_t keyAt(float d, float a1 = 0.0f, float a2 = 0.0f, float a3 = 0.0f) const {
    return q.key(feature(d, a1, a2, a3));
  }
};

TEST_F(QuantizerEdges, DistanceExactlyAtABinEdgeGoesToThatBin) {
  const float step = q.distanceStep();
  for (int k = 0; k <= 16; ++k) {
    const float edge = static_cast<float>(k) * step;
    const float centre = (static_cast<float>(k) + 0.5f) * step;
    SCOPED_TRACE(k);
    EXPECT_EQ(keyAt(edge), keyAt(std::min(centre, q.maxDistance()))) << "distance " << edge;
    if (k > 0) {
      EXPECT_LT(keyAt(std::nextafter(edge, 0.0f)), keyAt(edge)) << "just below the edge: bin k - 1";
      EXPECT_EQ(keyAt(std::nextafter(edge, 0.0f)), keyAt(centre - step));
    }
  }
}

TEST_F(QuantizerEdges, DistanceEdgesWithTheModelsOwnSteps) {
  // A realistic, non-dyadic step (4% of a 97 mm diameter): k * step computed in float still
  // lands in bin k for every bin of the model.
  const float diameter = 0.097f;
  const PpfQuantizer model_q(0.04f * diameter, rad(12.0f), diameter);
  const float step = model_q.distanceStep();
  for (int k = 0; static_cast<float>(k) * step <= diameter; ++k) {
    const float edge = static_cast<float>(k) * step;
    const float centre = std::min((static_cast<float>(k) + 0.5f) * step, diameter);
    EXPECT_EQ(model_q.key(feature(edge, 0, 0, 0)), model_q.key(feature(centre, 0, 0, 0)))
        << "distance k * step with k = " << k;
  }
}

TEST_F(QuantizerEdges, AngleExactlyAtABinEdgeGoesToThatBin) {
  const float step = q.angleStep();
  const int bins = static_cast<int>(std::ceil(kPi / step - 1e-4));
  for (int k = 0; k < bins; ++k) {
    const float edge = static_cast<float>(k) * step;
    const float centre = (static_cast<float>(k) + 0.5f) * step;
    SCOPED_TRACE(k);
    EXPECT_EQ(keyAt(1.0f, edge, 0, 0), keyAt(1.0f, centre, 0, 0));
    EXPECT_EQ(keyAt(1.0f, 0, edge, 0), keyAt(1.0f, 0, centre, 0));
    EXPECT_EQ(keyAt(1.0f, 0, 0, edge), keyAt(1.0f, 0, 0, centre));
  }
}

TEST_F(QuantizerEdges, LongPairsGetNoKeyAndExtremesStayInRange) {
  const float max = q.maxDistance();
  EXPECT_EQ(keyAt(std::nextafter(max, 10.0f)), -1);
  EXPECT_EQ(keyAt(2.0f * max), -1);
  EXPECT_EQ(keyAt(std::numeric_limits<float>::infinity()), -1);
  EXPECT_EQ(keyAt(std::numeric_limits<float>::quiet_NaN()), -1);

  // The longest hashed pair with angles at 0 and pi: valid keys, all distinct.
  const float pi = static_cast<float>(kPi);
  std::set<int64_t> keys;
  for (float d : {0.0f, max}) {
    for (float a1 : {0.0f, pi}) {
      for (float a2 : {0.0f, pi}) {
        for (float a3 : {0.0f, pi}) {
          const int64_t k = keyAt(d, a1, a2, a3);
          EXPECT_GE(k, 0);
          EXPECT_LT(k, q.keyCount());
          keys.insert(k);
        }
      }
    }
  }
  EXPECT_EQ(keys.size(), 16u) << "0 and pi must be different bins of every component";
  EXPECT_EQ(*keys.rbegin(), keyAt(max, pi, pi, pi));
  EXPECT_EQ(*keys.begin(), keyAt(0.0f, 0, 0, 0));
}

TEST_F(QuantizerEdges, DifferentBinsGiveDifferentKeys) {
  std::set<int64_t> keys;
  const float ds = q.distanceStep(), as = q.angleStep();
  int count = 0;
  for (int d = 0; d < 16; d += 3)
    for (int a1 = 0; a1 < 16; a1 += 5)
      for (int a2 = 0; a2 < 16; a2 += 5)
        for (int a3 = 0; a3 < 16; a3 += 5) {
          keys.insert(keyAt((d + 0.5f) * ds, (a1 + 0.5f) * as, (a2 + 0.5f) * as, (a3 + 0.5f) * as));
          ++count;
        }
  EXPECT_EQ(keys.size(), static_cast<std::size_t>(count));
}

TEST(PpfQuantizer, AlphaBinsCoverOneTurnAndWrapAnyAngle) {
  for (float step_deg : {12.0f, 5.0f, 30.0f, 7.0f}) {
    SCOPED_TRACE(step_deg);
    const PpfQuantizer q(0.004f, rad(step_deg), 0.1f);
    const int n = q.alphaBinCount();
    EXPECT_GE(n * q.angleStep(), kTwoPi * (1.0f - 1e-6f));
    EXPECT_LT((n - 1) * q.angleStep(), kTwoPi);

    for (int b = 0; b < n; ++b) {
      const float centre = q.alphaBinCentre(b);
      EXPECT_EQ(q.alphaBin(centre), b) << "centre round trip";
      EXPECT_EQ(q.alphaBin(centre + 2.0f * kTwoPi), b) << "4 pi + x";
      EXPECT_EQ(q.alphaBin(centre - kTwoPi), b) << "x - 2 pi";
      EXPECT_EQ(q.alphaBin(centre - 2.0f * kTwoPi), b) << "x - 4 pi";
    }
    EXPECT_EQ(q.alphaBin(-0.1f), q.alphaBin(kTwoPi - 0.1f));
    EXPECT_EQ(q.alphaBin(0.0f), 0);
    EXPECT_EQ(q.alphaBin(kTwoPi), q.alphaBin(0.0f));

    // The difference of two planar angles lies in (-2 pi, 2 pi): every value stays in range.
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<float> any(-4.0f * kTwoPi, 4.0f * kTwoPi);
    for (int i = 0; i < 2000; ++i) {
      const int bin = q.alphaBin(any(rng));
      ASSERT_GE(bin, 0);
      ASSERT_LT(bin, n);
    }
    for (float edge :
         {-kTwoPi, std::nextafter(0.0f, -1.0f), std::nextafter(kTwoPi, 0.0f), std::nextafter(-kTwoPi, 0.0f)}) {
      EXPECT_GE(q.alphaBin(edge), 0);
      EXPECT_LT(q.alphaBin(edge), n);
    }
  }
}

// The voting's fast path bins a - b for planar angles a, b in [-pi, pi]: the same bin as
// alphaBin(a - b) (a value within an ulp of a bin edge, 2 pi included, may land in either of the
// two bins that meet there).
TEST(PpfQuantizer, AlphaBinOfDifferenceAgreesWithAlphaBin) {
  const float pi = static_cast<float>(kPi);
  for (float step_deg : {12.0f, 5.0f, 30.0f, 7.0f}) {
    SCOPED_TRACE(step_deg);
    const PpfQuantizer q(0.004f, rad(step_deg), 0.1f);
    const int n = q.alphaBinCount();
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<float> angle(-pi, pi);
    for (int i = 0; i < 100000; ++i) {
      const float a = angle(rng), b = angle(rng);
      ASSERT_EQ(q.alphaBinOfDifference(a, b), q.alphaBin(a - b)) << "a = " << a << ", b = " << b;
    }
    for (int b = 0; b < n; ++b) {
      const float centre = q.alphaBinCentre(b);
      EXPECT_EQ(q.alphaBinOfDifference(centre - pi, -pi), b);
      EXPECT_EQ(q.alphaBinOfDifference(centre - pi, pi), b) << "centre - 2 pi";
    }
    const auto sameOrAdjacent = [n](int x, int y) {
      const int d = std::abs(x - y);
      return d == 0 || d == 1 || d == n - 1;
    };
    for (int k = -n; k <= n; ++k) {
      const float edge = static_cast<float>(k) * (kTwoPi / static_cast<float>(n));
      for (float b : {0.0f, 0.5f, -1.0f, pi, -pi}) {
        const float a = edge + b;
        if (a < -pi || a > pi) continue;
        const int fast = q.alphaBinOfDifference(a, b);
        ASSERT_GE(fast, 0);
        ASSERT_LT(fast, n);
        EXPECT_TRUE(sameOrAdjacent(fast, q.alphaBin(a - b))) << "a = " << a << ", b = " << b;
      }
    }
    for (const auto& [a, b] : {std::pair{pi, -pi}, std::pair{-pi, pi}, std::pair{0.0f, 0.0f}, std::pair{pi, pi},
                               std::pair{-1e-7f, 0.0f}, std::pair{0.0f, 1e-7f}}) {
      const int fast = q.alphaBinOfDifference(a, b);
      EXPECT_GE(fast, 0);
      EXPECT_LT(fast, n);
      EXPECT_TRUE(sameOrAdjacent(fast, q.alphaBin(a - b))) << "a = " << a << ", b = " << b;
    }
  }
}

// The table and the voting key a pair from cosines, not angles: the key of its feature (surface or
// boundary), but where float rounding puts an angle on the other side of a bin border; the
// normals' lengths do not count.
TEST(PpfQuantizer, PairKeyIsTheFeaturesKeyButAtBinBorders) {
  const auto nearBorder = [](float angle, float step) {
    return std::abs(angle - std::round(angle / step) * step) < 1e-5f;
  };
  for (float step_deg : {12.0f, 5.0f, 30.0f, 7.0f}) {
    SCOPED_TRACE(step_deg);
    const PpfQuantizer q(0.004f, rad(step_deg), 0.1f);
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<float> coord(-0.035f, 0.035f);
    int differing = 0, beyond = 0;
    for (int i = 0; i < 50000; ++i) {
      const Eigen::Vector3f pi(coord(rng), coord(rng), coord(rng)), pj(coord(rng), coord(rng), coord(rng));
      const Eigen::Vector3f ni = randomUnit(rng), nj = randomUnit(rng);
      const PointPairFeature f = computeFeature(pi, ni, pj, nj);
      const int64_t key = q.pairKey(pi, ni, pj, nj);
      // Scaling by powers of two is exact in float: the very same key.
      ASSERT_EQ(q.pairKey(pi, 2.0f * ni, pj, 0.25f * nj), key);
      beyond += key < 0;
      // The boundary pair's folded angles likewise, nj standing for a boundary line's direction.
      const PointPairFeature b = computeBoundaryFeature(pi, ni, pj, nj);
      const int64_t boundary_key = q.boundaryPairKey(pi, ni, pj, nj);
      for (const auto& [fast, feature] : {std::pair{key, f}, std::pair{boundary_key, b}}) {
        if (fast == q.key(feature)) continue;
        ++differing;
        ASSERT_GE(fast, 0) << "only the angles may differ";
        EXPECT_TRUE(nearBorder(feature.angle_ni_d, q.angleStep()) || nearBorder(feature.angle_nj_d, q.angleStep()) ||
                    nearBorder(feature.angle_ni_nj, q.angleStep()))
            << "pair " << i << ": keys " << fast << " and " << q.key(feature) << " away from any border";
      }
    }
    EXPECT_GT(beyond, 0) << "some pairs are longer than the maximum distance";
    EXPECT_LE(differing, 10);  // of 100000 keys
  }
  // Degenerate pairs take the angle 0 where atan2(0, 0) does: a zero normal, coincident points.
  const PpfQuantizer q(0.004f, rad(12.0f), 0.1f);
  const Eigen::Vector3f p(0.01f, 0.02f, 0.03f), n = Eigen::Vector3f(1, 2, 2).normalized();
  const Eigen::Vector3f far = p + Eigen::Vector3f(0.02f, -0.01f, 0.005f), zero = Eigen::Vector3f::Zero();
  EXPECT_EQ(q.pairKey(p, zero, far, n), q.key(computeFeature(p, zero, far, n)));
  EXPECT_EQ(q.pairKey(p, n, far, zero), q.key(computeFeature(p, n, far, zero)));
  EXPECT_EQ(q.pairKey(p, n, p, Eigen::Vector3f::UnitX()), q.key(computeFeature(p, n, p, Eigen::Vector3f::UnitX())));
  EXPECT_EQ(q.pairKey(p, n, p + Eigen::Vector3f(0.2f, 0, 0), n), -1);
  EXPECT_EQ(q.pairKey(p, n, Eigen::Vector3f::Constant(std::nanf("")), n), -1);
}

TEST(PpfQuantizer, RejectsNonsenseSteps) {
  using testing::errorMessage;
  EXPECT_NE(errorMessage([] { PpfQuantizer(0.0f, 0.2f, 0.1f); }), "");
  EXPECT_NE(errorMessage([] { PpfQuantizer(0.01f, 0.0f, 0.1f); }), "");
  EXPECT_NE(errorMessage([] { PpfQuantizer(0.01f, 0.2f, -1.0f); }), "");
  EXPECT_NE(errorMessage([] { PpfQuantizer(std::nanf(""), 0.2f, 0.1f); }), "");
  EXPECT_NE(errorMessage([] { PpfQuantizer(0.01f, 0.2f, std::numeric_limits<float>::infinity()); }), "");
  EXPECT_NE(errorMessage([] { PpfQuantizer(1e-6f, 0.2f, 1.0f); }), "") << "a million distance bins";
}

// Float tolerances: near n = -x the rotation is built from a dot product close to -1, whose
// float rounding alone is worth ~1e-4 rad (irrelevant next to 12 degree bins).
void expectReferenceFrame(const Eigen::Vector3f& p, const Eigen::Vector3f& n) {
  const Eigen::Isometry3f T = referenceFrame(p, n);
  EXPECT_LT((T * p).norm(), 1e-5f * std::max(1.0f, p.norm()));
  EXPECT_LT((T.linear() * n - Eigen::Vector3f::UnitX()).norm(), 3e-4f) << "n = " << n.transpose();
  EXPECT_LT((T.linear().transpose() * T.linear() - Eigen::Matrix3f::Identity()).norm(), 2e-4f);
  EXPECT_NEAR(T.linear().determinant(), 1.0f, 2e-4f);
}

TEST(ReferenceFrame, MapsPointToOriginAndNormalToPlusX) {
  expectReferenceFrame({0.1f, -0.2f, 0.3f}, Eigen::Vector3f::UnitX());
  expectReferenceFrame({0.1f, -0.2f, 0.3f}, -Eigen::Vector3f::UnitX());
  expectReferenceFrame({0, 0, 0}, -Eigen::Vector3f::UnitX());
  // Exactly +x and -x: exact frames (the antiparallel case is a half turn about a perpendicular).
  for (const Eigen::Vector3f& n :
       {Eigen::Vector3f(Eigen::Vector3f::UnitX()), Eigen::Vector3f(-Eigen::Vector3f::UnitX())}) {
    const Eigen::Isometry3f T = referenceFrame({0.3f, 0.1f, 0.7f}, n);
    EXPECT_LT((T.linear() * n - Eigen::Vector3f::UnitX()).norm(), 1e-6f);
    EXPECT_LT((T.linear().transpose() * T.linear() - Eigen::Matrix3f::Identity()).norm(), 1e-6f);
    EXPECT_LT((T * Eigen::Vector3f(0.3f, 0.1f, 0.7f)).norm(), 1e-6f);
  }
  expectReferenceFrame({0.5f, 0.5f, 0.9f}, Eigen::Vector3f(-1.0f, 1e-4f, 0.0f).normalized());
  expectReferenceFrame({0.5f, 0.5f, 0.9f}, Eigen::Vector3f(-1.0f, 0.0f, -1e-6f).normalized());
  expectReferenceFrame({0.5f, 0.5f, 0.9f}, Eigen::Vector3f::UnitY());
  expectReferenceFrame({0.5f, 0.5f, 0.9f}, -Eigen::Vector3f::UnitZ());
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<float> coord(-1.0f, 1.0f);
  for (int i = 0; i < 200; ++i) expectReferenceFrame({coord(rng), coord(rng), coord(rng)}, randomUnit(rng));
}

TEST(ReferenceFrame, PoseFromLocalCoordinateReproducesEquationTwo) {
  std::mt19937_64 rng(2018);
  std::uniform_real_distribution<float> coord(-0.05f, 0.05f);
  for (int trial = 0; trial < 500; ++trial) {
    const Eigen::Isometry3f T = randomPose(rng, 0.5f);
    const Eigen::Vector3f m_r(coord(rng), coord(rng), coord(rng)), m_i(coord(rng), coord(rng), coord(rng));
    if ((m_r - m_i).norm() < 0.01f) continue;
    // The reference normal must not be parallel to the pair: alpha is undefined then.
    Eigen::Vector3f n_r = randomUnit(rng);
    if (std::abs(n_r.dot((m_i - m_r).normalized())) > 0.95f) continue;
    const Eigen::Vector3f s_r = T * m_r, s_i = T * m_i, n_s = T.linear() * n_r;

    const Eigen::Isometry3f T_m = referenceFrame(m_r, n_r);
    const Eigen::Isometry3f T_s = referenceFrame(s_r, n_s);
    const float alpha = planarAngle(T_s * s_i) - planarAngle(T_m * m_i);
    const Eigen::Isometry3f pose = poseFromLocalCoordinate(T_s, T_m, alpha);
    SCOPED_TRACE(trial);
    EXPECT_LT((pose.matrix() - T.matrix()).cwiseAbs().maxCoeff(), 1e-4f);
    EXPECT_LT((pose * m_i - s_i).norm(), 1e-4f);
    // The same through the alpha bins: the bin's centre is at most half a bin away.
    const PpfQuantizer q(0.004f, rad(12.0f), 0.2f);
    const float binned = q.alphaBinCentre(q.alphaBin(alpha));
    const Eigen::Isometry3f coarse = poseFromLocalCoordinate(T_s, T_m, binned);
    EXPECT_LE(testing::rotationErrorDeg(coarse.linear(), T.linear()), 6.0 + 1e-3);
  }
}

}  // namespace
}  // namespace binpick::estimation
