// The model's PPF table (section II-A): every ordered pair under its key, and the validation of
// arrays adopted from a cache file.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "binpick/estimation/hash_table.hpp"
#include "estimation_test_support.hpp"

namespace binpick::estimation {
namespace {

using testing::errorMessage;
using testing::rad;
using testing::randomUnit;

struct Cloud {
  std::vector<Eigen::Vector3f> points, normals;
};

Cloud randomCloud(std::size_t n, float extent, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> coord(0.0f, extent);
  Cloud c;
  for (std::size_t i = 0; i < n; ++i) {
    c.points.emplace_back(coord(rng), coord(rng), coord(rng));
    c.normals.push_back(randomUnit(rng));
  }
  return c;
}

TEST(PpfHashTable, EveryOrderedPairIsFoundUnderItsKey) {
  const Cloud c = randomCloud(40, 0.05f, 5);
  // The cube's diagonal (0.087) is shorter than max_distance: every pair is hashed.
  const PpfQuantizer q(0.005f, rad(12.0f), 0.1f);
  const PpfHashTable table(c.points, c.normals, q);
  const std::size_t n = c.points.size();
  EXPECT_EQ(table.pairCount(), n * (n - 1));
  EXPECT_EQ(table.offsets().size(), static_cast<std::size_t>(q.keyCount()) + 1);

  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Isometry3f T_m = referenceFrame(c.points[i], c.normals[i]);
    for (std::size_t j = 0; j < n; ++j) {
      if (i == j) continue;
      const int64_t key = q.pairKey(c.points[i], c.normals[i], c.points[j], c.normals[j]);
      ASSERT_GE(key, 0);
      const PpfHashTable::Range range = table.lookup(key);
      const float alpha_m = planarAngle(T_m * c.points[j]);
      bool found = false;
      for (const PairEntry* e = range.begin; e != range.end && !found; ++e) {
        found = e->reference == i && std::abs(e->reference_angle - alpha_m) < 1e-5f;
      }
      EXPECT_TRUE(found) << "pair (" << i << ", " << j << ") missing under key " << key;
    }
  }

  // The ranges partition the entries: their sizes over all keys add up to the pair count.
  std::size_t total = 0;
  for (int64_t key = 0; key < q.keyCount(); ++key) {
    const auto range = table.lookup(key);
    total += static_cast<std::size_t>(range.end - range.begin);
  }
  EXPECT_EQ(total, table.pairCount());
}

TEST(PpfHashTable, CapKeepsAnEvenSubsetOfCrowdedKeys) {
  // Coplanar points with one normal: their pairs crowd a few keys, as a flat face's do.
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<float> coord(0.0f, 0.05f);
  Cloud c;
  for (int i = 0; i < 60; ++i) {
    c.points.emplace_back(coord(rng), coord(rng), 0.0f);
    c.normals.emplace_back(0.0f, 0.0f, 1.0f);
  }
  const PpfQuantizer q(0.01f, rad(12.0f), 0.1f);
  const PpfHashTable full(c.points, c.normals, q);
  const uint32_t cap = 50;
  const PpfHashTable capped(c.points, c.normals, q, cap);
  bool some_key_was_capped = false;
  for (int64_t key = 0; key < q.keyCount(); ++key) {
    const auto all = full.lookup(key), kept = capped.lookup(key);
    const auto n_all = static_cast<uint32_t>(all.end - all.begin),
               n_kept = static_cast<uint32_t>(kept.end - kept.begin);
    ASSERT_EQ(n_kept, std::min(n_all, cap)) << "key " << key;
    some_key_was_capped |= n_all > cap;
    // The kept pairs are pairs of the full key, taken in order and spread over all of them.
    const PairEntry* cursor = all.begin;
    for (const PairEntry* e = kept.begin; e != kept.end; ++e) {
      while (cursor != all.end && (cursor->reference != e->reference || cursor->reference_angle != e->reference_angle))
        ++cursor;
      ASSERT_NE(cursor, all.end) << "key " << key << ": a kept pair is not in the full table";
      ++cursor;
    }
    if (n_all > 2 * cap) {
      EXPECT_GT(kept.end[-1].reference, all.begin[n_all / 2].reference) << "the subset stops early at key " << key;
    }
  }
  EXPECT_TRUE(some_key_was_capped);
}

TEST(PpfHashTable, LongPairsAndOutOfRangeKeysAreNotStored) {
  const Cloud c = randomCloud(40, 0.1f, 9);
  const PpfQuantizer q(0.005f, rad(12.0f), 0.08f);  // shorter than some pairs
  const PpfHashTable table(c.points, c.normals, q);
  std::size_t short_pairs = 0;
  for (std::size_t i = 0; i < c.points.size(); ++i) {
    for (std::size_t j = 0; j < c.points.size(); ++j) {
      if (i != j && (c.points[j] - c.points[i]).norm() <= q.maxDistance()) ++short_pairs;
    }
  }
  ASSERT_LT(short_pairs, c.points.size() * (c.points.size() - 1)) << "the test needs some long pairs";
  EXPECT_EQ(table.pairCount(), short_pairs);

  for (int64_t key : {int64_t{-1}, q.keyCount(), q.keyCount() + 5}) {
    const auto range = table.lookup(key);
    EXPECT_EQ(range.begin, range.end) << "key " << key;
  }
  const PpfHashTable empty;
  EXPECT_EQ(empty.lookup(0).begin, empty.lookup(0).end);
  EXPECT_EQ(empty.pairCount(), 0u);
}

TEST(PpfHashTable, ValidatingConstructorAdoptsConsistentArrays) {
  const Cloud c = randomCloud(20, 0.05f, 1);
  const PpfQuantizer q(0.005f, rad(12.0f), 0.1f);
  const PpfHashTable built(c.points, c.normals, q);
  const PpfHashTable adopted(std::vector<uint32_t>(built.offsets().begin(), built.offsets().end()),
                             std::vector<PairEntry>(built.entries().begin(), built.entries().end()), 20);
  EXPECT_EQ(adopted.offsets(), built.offsets());
  ASSERT_EQ(adopted.entries().size(), built.entries().size());
  for (std::size_t k = 0; k < built.entries().size(); ++k) {
    EXPECT_EQ(adopted.entries()[k].reference, built.entries()[k].reference);
    EXPECT_EQ(adopted.entries()[k].reference_angle, built.entries()[k].reference_angle);
  }
  // A table without entries is consistent too.
  EXPECT_NO_THROW(PpfHashTable(std::vector<uint32_t>{0, 0, 0}, {}, 0));
}

TEST(PpfHashTable, ValidatingConstructorRejectsInconsistentArrays) {
  const std::vector<PairEntry> three{{0, 0.1f}, {1, 0.2f}, {2, -0.3f}};
  EXPECT_NO_THROW(PpfHashTable(std::vector<uint32_t>{0, 1, 1, 3}, three, 3));

  // Offsets that decrease (but still end at the entry count).
  EXPECT_NE(errorMessage([&] { PpfHashTable(std::vector<uint32_t>{0, 2, 1, 3}, three, 3); }), "");
  // Offsets that do not end at the entry count, or do not start at 0, or are missing.
  EXPECT_NE(errorMessage([&] { PpfHashTable(std::vector<uint32_t>{0, 1, 1, 2}, three, 3); }), "");
  EXPECT_NE(errorMessage([&] { PpfHashTable(std::vector<uint32_t>{0, 1, 1, 4}, three, 3); }), "");
  EXPECT_NE(errorMessage([&] { PpfHashTable(std::vector<uint32_t>{1, 1, 2, 3}, three, 3); }), "");
  EXPECT_NE(errorMessage([&] { PpfHashTable(std::vector<uint32_t>{}, three, 3); }), "");
  EXPECT_NE(errorMessage([&] { PpfHashTable(std::vector<uint32_t>{}, {}, 3); }), "");
  // Entries pointing at or past the point count, or with a non-finite angle.
  EXPECT_NE(errorMessage([&] { PpfHashTable(std::vector<uint32_t>{0, 1, 1, 3}, three, 2); }), "");
  std::vector<PairEntry> bad = three;
  bad[1].reference = 1000;
  EXPECT_NE(errorMessage([&] { PpfHashTable(std::vector<uint32_t>{0, 1, 1, 3}, bad, 3); }), "");
  bad = three;
  bad[2].reference_angle = std::nanf("");
  EXPECT_NE(errorMessage([&] { PpfHashTable(std::vector<uint32_t>{0, 1, 1, 3}, bad, 3); }), "");
}

}  // namespace
}  // namespace binpick::estimation
