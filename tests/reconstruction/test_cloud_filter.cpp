// Cloud filters on organized clouds: depth range, crop box, noise, depth-edge and speckle removal.
#include "binpick/reconstruction/cloud_filter.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>

#include "binpick/core/error.hpp"
#include "binpick/reconstruction/pixel_status.hpp"
#include "thrown_message.hpp"

namespace binpick::reconstruction {
namespace {

constexpr auto kValid = static_cast<uint8_t>(PixelStatus::Valid);
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// A plane tilted along x seen through a pinhole (f = 100 pixels): z from 0.7 to 0.8 m.
struct Grid {
  io::PointCloud cloud;
  cv::Mat status;
  Eigen::Vector3f& at(int x, int y) { return cloud.points[static_cast<std::size_t>(y) * cloud.width + x]; }
  uint8_t statusAt(int x, int y) const { return status.at<uint8_t>(y, x); }
};

Grid tiltedPlane(int width = 100, int height = 80) {
  Grid g;
  g.cloud.width = width;
  g.cloud.height = height;
  g.status = cv::Mat(height, width, CV_8UC1, cv::Scalar(kValid));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      // Neighbours differ by at most 1 mm in z: one connected surface for the default step.
      const float z = 0.7f + 0.1f * static_cast<float>(x) / static_cast<float>(width);
      g.cloud.points.emplace_back(z * (x - width / 2) / 100.0f, z * (y - height / 2) / 100.0f, z);
    }
  }
  return g;
}

// Neither noise, speckle nor depth-edge removal: the filter under test alone.
CloudFilterParams noSpeckle() {
  CloudFilterParams params;
  params.speckle_min_pixels = 0;
  params.median_reach = 0.0;
  params.edge_max_jump = 0.0;
  return params;
}

// Speckle removal alone (the noise and depth-edge filters would take the single stray points
// first).
CloudFilterParams speckleOnly() {
  CloudFilterParams params;
  params.median_reach = 0.0;
  params.edge_max_jump = 0.0;
  return params;
}

std::size_t count(const Grid& g, PixelStatus status) {
  return countStatuses(g.status)[static_cast<std::size_t>(status)];
}

// Every pixel either keeps its point and status or has a NaN point and the expected status.
void expectRemovedExactly(const Grid& before, const Grid& after, PixelStatus reason,
                          const std::function<bool(const Eigen::Vector3f&)>& removed) {
  for (std::size_t i = 0; i < before.cloud.size(); ++i) {
    const Eigen::Vector3f& p = before.cloud.points[i];
    const uint8_t status = after.status.ptr<uint8_t>(0)[i];
    if (p.allFinite() && removed(p)) {
      EXPECT_TRUE(after.cloud.points[i].array().isNaN().all()) << i;
      EXPECT_EQ(status, static_cast<uint8_t>(reason)) << i;
    } else {
      EXPECT_TRUE(after.cloud.points[i] == p || (!p.allFinite() && !after.cloud.points[i].allFinite())) << i;
      EXPECT_EQ(status, before.status.ptr<uint8_t>(0)[i]) << i;
    }
  }
}

TEST(CloudFilter, DepthRangeRemovesPointsOutsideIt) {
  const Grid before = tiltedPlane();
  Grid after = before;
  CloudFilterParams params = noSpeckle();
  params.min_depth = 0.72;
  params.max_depth = 0.78;
  filterCloud(after.cloud, after.status, params);
  expectRemovedExactly(before, after, PixelStatus::OutOfDepthRange,
                       [](const Eigen::Vector3f& p) { return p.z() < 0.72f || p.z() > 0.78f; });
  EXPECT_GT(count(after, PixelStatus::OutOfDepthRange), 3000u);
}

TEST(CloudFilter, CropBoxRemovesPointsOutsideIt) {
  const Grid before = tiltedPlane();
  Grid after = before;
  CloudFilterParams params = noSpeckle();
  params.crop = Eigen::AlignedBox3d(Eigen::Vector3d(-0.1, -0.2, 0.0), Eigen::Vector3d(0.2, 0.1, 2.0));
  filterCloud(after.cloud, after.status, params);
  const Eigen::AlignedBox3d crop = params.crop;
  expectRemovedExactly(before, after, PixelStatus::OutsideCrop,
                       [&](const Eigen::Vector3f& p) { return !crop.contains(p.cast<double>()); });
  EXPECT_GT(count(after, PixelStatus::OutsideCrop), 1000u);
  EXPECT_GT(count(after, PixelStatus::Valid), 1000u);
}

TEST(CloudFilter, DefaultsKeepEveryPointOfASmoothSurface) {
  const Grid before = tiltedPlane();
  Grid after = before;
  filterCloud(after.cloud, after.status, CloudFilterParams{});
  expectRemovedExactly(before, after, PixelStatus::Valid, [](const Eigen::Vector3f&) { return false; });
}

TEST(CloudFilter, PixelsWithoutPointsKeepTheirStatus) {
  Grid g = tiltedPlane();
  for (int x = 0; x < 100; ++x) {
    g.at(x, 10) = Eigen::Vector3f::Constant(kNaN);
    g.status.at<uint8_t>(10, x) = static_cast<uint8_t>(PixelStatus::Unlit);
  }
  CloudFilterParams params;
  params.max_depth = 0.75;
  filterCloud(g.cloud, g.status, params);
  EXPECT_GT(count(g, PixelStatus::OutOfDepthRange), 1000u);
  for (int x = 0; x < 100; ++x) EXPECT_EQ(g.statusAt(x, 10), static_cast<uint8_t>(PixelStatus::Unlit));
}

// A surface with stray patches: one floating 3 cm in front of it, one cut off by a ring of
// missing points, and single pixels.
TEST(CloudFilter, SpeckleRemovalRemovesSmallIsolatedPatchesAndKeepsLargeSurfaces) {
  Grid g = tiltedPlane();
  for (int y = 20; y < 25; ++y) {
    for (int x = 20; x < 25; ++x) g.at(x, y).z() -= 0.03f;  // 25 points, floating
  }
  for (int y = 50; y < 58; ++y) {
    for (int x = 60; x < 68; ++x) {
      const bool ring = y == 50 || y == 57 || x == 60 || x == 67;
      if (!ring) continue;  // 6 x 6 = 36 points inside
      g.at(x, y) = Eigen::Vector3f::Constant(kNaN);
      g.status.at<uint8_t>(y, x) = static_cast<uint8_t>(PixelStatus::UncertainCode);
    }
  }
  g.at(90, 70).z() += 0.01f;  // a single outlier
  // A 10 x 10 patch floating but larger than the limit, and a diagonal-only neighbour of the
  // first patch (4-connectivity: its own patch).
  for (int y = 60; y < 70; ++y) {
    for (int x = 5; x < 15; ++x) g.at(x, y).z() -= 0.05f;
  }
  g.at(25, 25).z() -= 0.03f;
  const Grid before = g;
  CloudFilterParams params = speckleOnly();
  params.speckle_min_pixels = 50;
  params.speckle_max_step = 0.002;
  filterCloud(g.cloud, g.status, params);
  auto speckle = [&](int x, int y) {
    return g.statusAt(x, y) == static_cast<uint8_t>(PixelStatus::Speckle) && g.at(x, y).array().isNaN().all();
  };
  EXPECT_TRUE(speckle(22, 22));
  EXPECT_TRUE(speckle(63, 53));
  EXPECT_TRUE(speckle(90, 70));
  EXPECT_TRUE(speckle(25, 25));
  EXPECT_FALSE(speckle(10, 65));  // 100 points: kept
  EXPECT_EQ(count(g, PixelStatus::Speckle), 25u + 36u + 1u + 1u);
  EXPECT_EQ(count(g, PixelStatus::Valid), before.cloud.size() - 28u - 63u);  // 28: the ring
  EXPECT_TRUE(g.at(0, 0) == before.cloud.points[0]);
}

TEST(CloudFilter, SpeckleRemovalTurnsOffWithZeroMinimum) {
  Grid g = tiltedPlane();
  g.at(50, 40).z() += 0.1f;
  const Grid before = g;
  filterCloud(g.cloud, g.status, noSpeckle());
  expectRemovedExactly(before, g, PixelStatus::Valid, [](const Eigen::Vector3f&) { return false; });
}

// A slanted surface decoded to whole codes (no phase) is a staircase: terraces one code wide whose
// depth steps by what a code spans there (here 5 mm, beyond the fixed 2 mm speckle step). Told
// the code depth, the speckle filter keeps the staircase as one surface; not told, every terrace
// is a patch of its own, too small to keep.
TEST(CloudFilter, SpeckleStepsFollowTheDepthACodeSpans) {
  const auto staircase = [] {
    Grid g = tiltedPlane(120, 10);
    for (int y = 0; y < 10; ++y) {
      for (int x = 0; x < 120; ++x) g.at(x, y).z() = 0.7f + 0.005f * static_cast<float>(x / 4);  // 40 points a terrace
    }
    return g;
  };
  Grid told = staircase();
  const cv::Mat code_depth(10, 120, CV_32FC1, cv::Scalar(0.004));  // 1.5 codes: 6 mm
  filterCloud(told.cloud, told.status, speckleOnly(), {cv::Mat(), code_depth});
  EXPECT_EQ(count(told, PixelStatus::Valid), 1200u);

  Grid untold = staircase();
  filterCloud(untold.cloud, untold.status, speckleOnly());
  EXPECT_EQ(count(untold, PixelStatus::Speckle), 1200u);

  CloudFilterParams fixed_steps = speckleOnly();
  fixed_steps.min_step_in_codes = 0.0;
  Grid off = staircase();
  filterCloud(off.cloud, off.status, fixed_steps, {cv::Mat(), code_depth});
  EXPECT_EQ(count(off, PixelStatus::Speckle), 1200u) << "min_step_in_codes: 0 must leave the fixed step alone";
}

// The same through the depth-edge test, with terraces one column wide and a reach of half a
// footprint (at most 4.5 mm here): each point has only its own column's 2 neighbours within reach,
// unless a code's depth is.
TEST(CloudFilter, DepthEdgeReachFollowsTheDepthACodeSpans) {
  const auto staircase = [] {
    Grid g = tiltedPlane(40, 10);
    for (int y = 0; y < 10; ++y) {
      for (int x = 0; x < 40; ++x) g.at(x, y).z() = 0.7f + 0.005f * static_cast<float>(x);
    }
    return g;
  };
  CloudFilterParams edges_only = speckleOnly();
  edges_only.speckle_min_pixels = 0;
  edges_only.edge_max_jump = 0.5;
  edges_only.edge_side_reach = 0;
  Grid told = staircase();
  filterCloud(told.cloud, told.status, edges_only, {cv::Mat(), cv::Mat(10, 40, CV_32FC1, cv::Scalar(0.004))});
  EXPECT_EQ(count(told, PixelStatus::DepthEdge), 0u);
  Grid untold = staircase();
  filterCloud(untold.cloud, untold.status, edges_only);
  EXPECT_EQ(count(untold, PixelStatus::DepthEdge), 400u);
}

// Random outliers sprinkled over a large surface: every one goes, the surface stays.
TEST(CloudFilter, SpeckleRemovalCleansSprinkledOutliers) {
  Grid g = tiltedPlane(400, 300);
  std::mt19937 random(9);
  std::uniform_int_distribution<int> column(0, 399), row(0, 299);
  std::size_t outliers = 0;
  for (int k = 0; k < 300; ++k) {
    Eigen::Vector3f& p = g.at(column(random), row(random));
    if (p.z() < 0.5f) continue;  // already moved
    p.z() -= 0.5f;
    ++outliers;
  }
  filterCloud(g.cloud, g.status, speckleOnly());
  // Outliers that happen to touch form patches of 2 or 3: still far below the limit.
  EXPECT_EQ(count(g, PixelStatus::Speckle), outliers);
  for (const Eigen::Vector3f& p : g.cloud.points) EXPECT_FALSE(p.z() < 0.5f);
}

// Bands of rows are labelled on separate threads and joined along their edges: a patch that
// straddles an edge is one patch, and the result is the same on any number of threads.
TEST(CloudFilter, SpecklePatchesAcrossThreadBandsAreWholeAndResultsDoNotDependOnThreads) {
  Grid base = tiltedPlane(120, 90);
  // A 6 x 10 patch floating 5 cm above the plane, centred on the edge between two bands (row 45
  // for 2 threads, rows 30 and 60 for 3): 60 pixels, kept as a whole; each half alone would go.
  for (int y = 40; y < 50; ++y) {
    for (int x = 10; x < 16; ++x) base.at(x, y).z() -= 0.05f;
  }
  for (int y = 25; y < 35; ++y) {
    for (int x = 20; x < 26; ++x) base.at(x, y).z() -= 0.05f;
  }
  base.at(100, 30).z() -= 0.05f;  // one stray point on a band edge: removed
  std::vector<cv::Mat> statuses;
  for (int threads : {1, 2, 3, 7}) {
    Grid g = base;
    g.status = base.status.clone();
    CloudFilterParams params = speckleOnly();
    params.threads = threads;
    filterCloud(g.cloud, g.status, params);
    EXPECT_EQ(count(g, PixelStatus::Speckle), 1u) << threads << " threads";
    statuses.push_back(g.status);
  }
  for (const cv::Mat& status : statuses) EXPECT_EQ(cv::norm(status, statuses.front(), cv::NORM_INF), 0.0);
}

// An organized cloud through a 1600 px pinhole (the virtual camera's focal length): z per pixel.
Grid pinholeCloud(int width, int height, const std::function<float(int, int)>& depth) {
  Grid g;
  g.cloud.width = width;
  g.cloud.height = height;
  g.status = cv::Mat(height, width, CV_8UC1, cv::Scalar(kValid));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float z = depth(x, y);
      g.cloud.points.emplace_back(z * (x - width / 2) / 1600.0f, z * (y - height / 2) / 1600.0f, z);
    }
  }
  return g;
}

// A near surface (0.80 m) beside a far one (0.86 m), and between them a column of mixed pixels:
// each saw part of both, and decoded to a depth in between that drifts along the edge.
TEST(CloudFilter, DepthEdgeRemovalTakesMixedPixelsBetweenANearAndAFarSurface) {
  const Grid before = pinholeCloud(120, 90, [](int x, int y) {
    if (x < 60) return 0.80f;
    if (x > 60) return 0.86f;
    return 0.80f + 0.06f * (0.2f + 0.6f * static_cast<float>(y) / 89.0f);  // 12 to 48 mm behind
  });
  Grid after = before;
  filterCloud(after.cloud, after.status, CloudFilterParams{});
  for (int y = 0; y < 90; ++y) {
    EXPECT_EQ(after.statusAt(60, y), static_cast<uint8_t>(PixelStatus::DepthEdge)) << y;
    EXPECT_TRUE(after.at(60, y).array().isNaN().all()) << y;
  }
  // Both surfaces keep every point, their last pixels at the edge included.
  EXPECT_EQ(count(after, PixelStatus::Valid), before.cloud.size() - 90u);
}

// The same veil where the far surface lies in projector shadow (no points): the mixed pixels
// hang off the near surface's edge.
TEST(CloudFilter, DepthEdgeRemovalTakesMixedPixelsBesideAShadow) {
  const float nan = kNaN;
  Grid g = pinholeCloud(120, 90, [nan](int x, int y) {
    if (x < 60) return 0.80f;
    if (x > 60) return nan;
    return 0.81f + 0.03f * static_cast<float>(y % 7) / 7.0f;
  });
  filterCloud(g.cloud, g.status, CloudFilterParams{});
  EXPECT_EQ(count(g, PixelStatus::DepthEdge), 90u);
  const auto finite = std::count_if(g.cloud.points.begin(), g.cloud.points.end(),
                                    [](const Eigen::Vector3f& p) { return p.allFinite(); });
  EXPECT_EQ(finite, 60 * 90);  // the near surface, whole
}

// A near surface (0.80 m, white image 0.6) whose projector shadow falls on the right (unlit,
// 0.02): its columns up to 59 see it, the last with 80% of its area (0.49); column 60's centre
// sees the shadow, but its area and blur take in 35% of the lit edge (0.22): it decoded the
// edge's light and has its point on the surface's extension. Column 60 goes, 59 stays.
// `brightness` gives the white image per column (intensities of the pixels without a point too).
Grid litEdgeBesideAShadow(const std::function<float(int)>& brightness) {
  Grid g = pinholeCloud(120, 90, [](int x, int) { return x <= 60 ? 0.80f + 0.0001f * x : kNaN; });
  for (int y = 0; y < 90; ++y) {
    for (int x = 0; x < 120; ++x) {
      g.cloud.intensities.push_back(brightness(x));
      if (x > 60) g.status.at<uint8_t>(y, x) = static_cast<uint8_t>(PixelStatus::Unlit);
    }
  }
  return g;
}

float blurredEdge(int x) { return x < 59 ? 0.6f : x == 59 ? 0.49f : x == 60 ? 0.22f : 0.02f; }

// A copy that owns its status image (cv::Mat copies share their pixels).
Grid copyOf(const Grid& g) {
  Grid copy = g;
  copy.status = g.status.clone();
  return copy;
}

TEST(CloudFilter, DepthEdgeRemovalTakesEdgePixelsThatSeeTheShadow) {
  const Grid before = litEdgeBesideAShadow(blurredEdge);
  Grid after = copyOf(before);
  filterCloud(after.cloud, after.status, CloudFilterParams{});
  expectRemovedExactly(before, after, PixelStatus::DepthEdge,
                       [](const Eigen::Vector3f& p) { return p.z() > 0.80595f; });
  EXPECT_EQ(count(after, PixelStatus::DepthEdge), 90u);
  // Off, or without the white image to judge by, the pixels stay (the depth-step test alone keeps
  // them: they continue the surface).
  Grid off = copyOf(before);
  CloudFilterParams params;
  params.edge_side_reach = 0;
  filterCloud(off.cloud, off.status, params);
  EXPECT_EQ(count(off, PixelStatus::DepthEdge), 0u);
  Grid dark = copyOf(before);
  dark.cloud.intensities.clear();
  filterCloud(dark.cloud, dark.status, CloudFilterParams{});
  EXPECT_EQ(count(dark, PixelStatus::DepthEdge), 0u);
}

// Beside the same shadow, a dimmer face beyond a crease (3 columns at 0.25 next to 0.6, as a
// steep side face is) and a sharp edge (no blur: the last column as bright as the rest) keep
// every point.
TEST(CloudFilter, DepthEdgeRemovalKeepsADimFaceBesideAShadow) {
  for (const auto& brightness : std::vector<std::function<float(int)>>{[](int x) {
                                                                         return x < 58 ? 0.6f : x <= 60 ? 0.25f : 0.02f;
                                                                       },
                                                                       [](int x) { return x <= 60 ? 0.6f : 0.02f; }}) {
    Grid g = litEdgeBesideAShadow(brightness);
    filterCloud(g.cloud, g.status, CloudFilterParams{});
    EXPECT_EQ(count(g, PixelStatus::DepthEdge), 0u);
    EXPECT_EQ(count(g, PixelStatus::Valid), 61u * 90u);
  }
}

// The same near surface over a lit floor 60 mm further (white image 0.15) instead of a shadow:
// column 60's centre sees the floor, but it gathers enough of the edge (0.25) to decode the
// edge's light, and its point hangs on the near surface's extension 60 mm above the floor. It
// goes; column 59, the floor and, with a sharp edge, every point stay.
TEST(CloudFilter, DepthEdgeRemovalTakesEdgePixelsThatSeeALitSurfaceBehind) {
  const auto overALitFloor = [](const std::function<float(int)>& brightness) {
    Grid g = pinholeCloud(120, 90, [](int x, int) { return x <= 60 ? 0.80f + 0.0001f * x : 0.86f; });
    for (int y = 0; y < 90; ++y) {
      for (int x = 0; x < 120; ++x) g.cloud.intensities.push_back(brightness(x));
    }
    return g;
  };
  const Grid before = overALitFloor([](int x) { return x < 59 ? 0.6f : x == 59 ? 0.49f : x == 60 ? 0.25f : 0.15f; });
  Grid after = copyOf(before);
  filterCloud(after.cloud, after.status, CloudFilterParams{});
  expectRemovedExactly(before, after, PixelStatus::DepthEdge,
                       [](const Eigen::Vector3f& p) { return p.z() > 0.80595f && p.z() < 0.85f; });
  EXPECT_EQ(count(after, PixelStatus::DepthEdge), 90u);
  Grid sharp = overALitFloor([](int x) { return x <= 60 ? 0.6f : 0.15f; });
  filterCloud(sharp.cloud, sharp.status, CloudFilterParams{});
  EXPECT_EQ(count(sharp, PixelStatus::DepthEdge), 0u);
}

// A plane seen 75 degrees from its normal (2 mm between neighbours along the slope), with
// 0.3 mm noise, and a gently curved one: nothing is removed.
TEST(CloudFilter, DepthEdgeRemovalKeepsSlantedAndCurvedSurfaces) {
  const double slope = std::tan(75.0 * M_PI / 180.0);
  std::mt19937 random(5);
  std::normal_distribution<float> noise(0.0f, 0.0003f);
  Grid slanted = pinholeCloud(160, 120, [&](int x, int) {
    // Ray (u, v, 1) / f against the plane z = 0.85 + slope * X: z = 0.85 / (1 - slope * u / f).
    const double u = (x - 80) / 1600.0;
    return static_cast<float>(0.85 / (1.0 - slope * u)) + noise(random);
  });
  Grid curved = pinholeCloud(160, 120, [](int x, int y) {
    const float r = std::hypot(static_cast<float>(x - 80), static_cast<float>(y - 60)) / 1600.0f;
    return 0.8f + 8.0f * r * r;  // a bowl, 30 mm deep at the corners
  });
  for (Grid* g : {&slanted, &curved}) {
    filterCloud(g->cloud, g->status, CloudFilterParams{});
    EXPECT_EQ(count(*g, PixelStatus::Valid), g->cloud.size());
  }
}

TEST(CloudFilter, DepthEdgeRemovalTakesLoneMisdecodedPoints) {
  Grid g = pinholeCloud(100, 80, [](int, int) { return 0.85f; });
  g.at(30, 30).z() += 0.01f;  // 10 mm off: 19 footprints
  g.at(70, 50).z() -= 0.006f;
  g.at(71, 50).z() -= 0.006f;  // two adjacent: each has one neighbour of its own
  filterCloud(g.cloud, g.status, CloudFilterParams{});
  EXPECT_EQ(count(g, PixelStatus::DepthEdge), 3u);
  EXPECT_EQ(count(g, PixelStatus::Speckle), 0u);
}

// Noise removal alone.
// Noise removal alone, on every dark point (these clouds come without the decoder's column noise).
CloudFilterParams medianOnly() {
  CloudFilterParams params = noSpeckle();
  params.median_reach = 0.0045;
  params.median_min_noise = 0.0;
  return params;
}

double rmsErrorMm(const Grid& g, float true_z) {
  double sum = 0.0;
  std::size_t n = 0;
  for (const Eigen::Vector3f& p : g.cloud.points) {
    if (!p.allFinite()) continue;
    sum += (p.z() - true_z) * (p.z() - true_z);
    ++n;
  }
  return std::sqrt(sum / static_cast<double>(n)) * 1000.0;
}

// A flat dark surface 0.85 m away with 1 mm of depth noise: the median of each point's
// neighbourhood has about half the noise; a point more than 3.2 mm from it is removed; every
// other point stays on its ray.
TEST(CloudFilter, NoiseRemovalHalvesTheNoiseOfASurfaceAndKeepsItsPoints) {
  std::mt19937 random(3);
  std::normal_distribution<float> noise(0.0f, 0.001f);
  const Grid before = pinholeCloud(160, 120, [&](int, int) { return 0.85f + noise(random); });
  Grid after = before;
  filterCloud(after.cloud, after.status, medianOnly());
  EXPECT_LT(rmsErrorMm(after, 0.85f), 0.6 * rmsErrorMm(before, 0.85f));
  EXPECT_GT(count(after, PixelStatus::Valid), before.cloud.size() * 99 / 100);
  EXPECT_EQ(count(after, PixelStatus::Valid) + count(after, PixelStatus::DepthEdge), before.cloud.size());
  for (std::size_t i = 0; i < before.cloud.size(); ++i) {
    const Eigen::Vector3f& p = after.cloud.points[i];
    if (!p.allFinite()) continue;
    const Eigen::Vector3f& q = before.cloud.points[i];
    EXPECT_NEAR(p.x() / p.z(), q.x() / q.z(), 1e-6f) << i;  // the same camera ray
    EXPECT_NEAR(p.z(), 0.85f, 0.004f) << i;
  }
}

// A point 3.5 mm off a plane (within the 4.5 mm reach, so its neighbours are its surface) is
// removed; its neighbours' medians are the plane's and they stay where they are. A point farther
// off has no neighbour within reach: it is left to the depth-edge filter.
TEST(CloudFilter, NoiseRemovalTakesAPointOffItsNeighboursSurface) {
  const Grid before = pinholeCloud(100, 80, [](int x, int y) { return x == 40 && y == 30 ? 0.8535f : 0.85f; });
  Grid after = before;
  filterCloud(after.cloud, after.status, medianOnly());
  EXPECT_EQ(after.statusAt(40, 30), static_cast<uint8_t>(PixelStatus::DepthEdge));
  expectRemovedExactly(before, after, PixelStatus::DepthEdge, [](const Eigen::Vector3f& p) { return p.z() > 0.851f; });
}

// At a depth edge 20 mm high and along a slope of 2 mm per pixel (75 degrees from the view), the median is of the
// point's own surface: nothing moves across the edge and nothing is removed.
TEST(CloudFilter, NoiseRemovalKeepsDepthEdgesAndSlopes) {
  const Grid step = pinholeCloud(100, 80, [](int x, int) { return x < 50 ? 0.83f : 0.85f; });
  const Grid slope = pinholeCloud(100, 80, [](int x, int) { return 0.8f + 0.002f * static_cast<float>(x); });
  for (const Grid* before : {&step, &slope}) {
    Grid after = *before;
    filterCloud(after.cloud, after.status, medianOnly());
    for (std::size_t i = 0; i < before->cloud.size(); ++i) {
      EXPECT_NEAR(after.cloud.points[i].z(), before->cloud.points[i].z(), 1e-6f) << i;
    }
  }
}

// With intensities, only the dark points are smoothed: the bright half of the surface keeps its
// points as they were.
TEST(CloudFilter, NoiseRemovalLeavesBrightPointsAsTheyAre) {
  std::mt19937 random(6);
  std::normal_distribution<float> noise(0.0f, 0.001f);
  const Grid before = pinholeCloud(160, 120, [&](int, int) { return 0.85f + noise(random); });
  Grid after = before;
  after.cloud.intensities.resize(before.cloud.size());
  for (std::size_t i = 0; i < before.cloud.size(); ++i) after.cloud.intensities[i] = i % 160 < 80 ? 0.1f : 0.5f;
  filterCloud(after.cloud, after.status, medianOnly());
  std::size_t dark_moved = 0;
  for (std::size_t i = 0; i < before.cloud.size(); ++i) {
    if (i % 160 >= 80) {
      EXPECT_TRUE(after.cloud.points[i] == before.cloud.points[i]) << i;
      EXPECT_EQ(after.status.ptr<uint8_t>(0)[i], kValid) << i;
    } else {
      dark_moved += after.cloud.points[i] == before.cloud.points[i] ? 0 : 1;
    }
  }
  EXPECT_GT(dark_moved, 80u * 118u / 2u);
}

// The foot of a steep face (5 mm per pixel, beyond the 4.5 mm reach up the slope) 2 mm above the
// floor: the floor lies within reach on one side only. The mean of opposite neighbours is the
// face's own depth (along its level line), so the foot stays where it is; a median of the
// neighbours within reach would have pulled it 2 mm onto the floor. The floor beside it, whose
// lines across the 2 mm step are within reach, moves at most half the step towards it: a step
// lower than median_reach is rounded, never crossed.
TEST(CloudFilter, NoiseRemovalKeepsTheFootOfASteepFaceOffTheFloor) {
  const auto depth = [](int x, int) { return x < 50 ? 0.848f - 0.005f * static_cast<float>(49 - x) : 0.85f; };
  const Grid before = pinholeCloud(100, 80, depth);
  Grid after = before;
  filterCloud(after.cloud, after.status, medianOnly());
  for (int y = 1; y < 79; ++y) {
    EXPECT_NEAR(after.at(49, y).z(), 0.848f, 1e-6f) << y;  // the foot
    EXPECT_LE(after.at(50, y).z(), 0.85f + 1e-6f) << y;    // the floor beside it
    EXPECT_GE(after.at(50, y).z(), 0.849f - 1e-6f) << y;
    EXPECT_NEAR(after.at(51, y).z(), 0.85f, 1e-6f) << y;
  }
}

// Given the decoder's column noise, only the noisy points are smoothed: a surface measured to
// 0.1 projector pixel keeps its points as measured, however dark; without the noise, a cloud is
// not smoothed unless median_min_noise is 0.
TEST(CloudFilter, NoiseRemovalSmoothsOnlyThePointsTheDecoderMeasuredNoisily) {
  std::mt19937 random(8);
  std::normal_distribution<float> noise(0.0f, 0.001f);
  const Grid before = pinholeCloud(160, 120, [&](int, int) { return 0.85f + noise(random); });
  cv::Mat column_noise(120, 160, CV_32FC1);
  for (int y = 0; y < 120; ++y) {
    for (int x = 0; x < 160; ++x) column_noise.at<float>(y, x) = x < 80 ? 0.5f : 0.1f;
  }
  CloudFilterParams params = noSpeckle();
  params.median_reach = 0.0045;  // median_min_noise as by default: 0.3 px
  Grid after = before;
  filterCloud(after.cloud, after.status, params, {column_noise, cv::Mat()});
  std::size_t noisy_moved = 0;
  for (int y = 0; y < 120; ++y) {
    for (int x = 0; x < 160; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * 160 + x;
      if (x >= 80) {
        EXPECT_TRUE(after.cloud.points[i] == before.cloud.points[i]) << x << "," << y;
      } else {
        noisy_moved += after.cloud.points[i] == before.cloud.points[i] ? 0 : 1;
      }
    }
  }
  EXPECT_GT(noisy_moved, 80u * 118u / 2u);
  Grid unknown = before;
  filterCloud(unknown.cloud, unknown.status, params);
  for (std::size_t i = 0; i < before.cloud.size(); ++i) EXPECT_TRUE(unknown.cloud.points[i] == before.cloud.points[i]);
}

// A noisy point on no line of its neighbourhood's surface (the points beside it on every line are
// missing) has nothing to be checked with: it is removed when its column noise exceeds
// median_lone_max_noise, kept otherwise.
TEST(CloudFilter, NoiseRemovalTakesLoneNoisyPoints) {
  Grid before = pinholeCloud(40, 30, [](int, int) { return 0.85f; });
  for (const auto& [x, y] : {std::pair{10, 10}, std::pair{30, 20}}) {
    // The left column of the neighbourhood and the point above: every line has an end missing.
    for (int dy = -1; dy <= 1; ++dy) before.at(x - 1, y + dy) = Eigen::Vector3f::Constant(kNaN);
    before.at(x, y - 1) = Eigen::Vector3f::Constant(kNaN);
  }
  cv::Mat column_noise(30, 40, CV_32FC1, cv::Scalar(0.5f));
  column_noise.at<float>(10, 10) = 0.8f;  // above median_lone_max_noise (0.6)
  CloudFilterParams params = noSpeckle();
  params.median_reach = 0.0045;
  Grid after = before;
  filterCloud(after.cloud, after.status, params, {column_noise, cv::Mat()});
  EXPECT_EQ(after.statusAt(10, 10), static_cast<uint8_t>(PixelStatus::DepthEdge));
  EXPECT_FALSE(after.at(10, 10).allFinite());
  EXPECT_EQ(after.statusAt(30, 20), kValid);
  EXPECT_TRUE(after.at(30, 20) == before.at(30, 20));
}

TEST(CloudFilter, NoiseRemovalDoesNotDependOnTheThreadCount) {
  std::mt19937 random(4);
  std::normal_distribution<float> noise(0.0f, 0.002f);
  const Grid before = pinholeCloud(160, 120, [&](int x, int) { return 0.8f + 0.0005f * x + noise(random); });
  CloudFilterParams params = medianOnly();
  params.threads = 1;
  Grid one = before;
  filterCloud(one.cloud, one.status, params);
  params.threads = 3;
  Grid three = before;
  filterCloud(three.cloud, three.status, params);
  EXPECT_EQ(cv::norm(one.status, three.status, cv::NORM_INF), 0.0);
  for (std::size_t i = 0; i < before.cloud.size(); ++i) {
    EXPECT_TRUE(one.cloud.points[i] == three.cloud.points[i] ||
                (!one.cloud.points[i].allFinite() && !three.cloud.points[i].allFinite()))
        << i;
  }
}

TEST(CloudFilter, DepthEdgeParamsAreChecked) {
  CloudFilterParams params;
  params.edge_max_jump = -1.0;
  EXPECT_TRUE(test::throwsNaming([&] { params.validate(); }, "edge_max_jump"));
  params = CloudFilterParams{};
  params.edge_min_support = 9;
  EXPECT_TRUE(test::throwsNaming([&] { params.validate(); }, "edge_min_support"));
  params = CloudFilterParams{};
  params.edge_min_neighbours = 0;
  EXPECT_TRUE(test::throwsNaming([&] { params.validate(); }, "edge_min_neighbours"));
  params = CloudFilterParams{};
  params.edge_side_reach = -1;
  EXPECT_TRUE(test::throwsNaming([&] { params.validate(); }, "edge_side_reach"));
  params = CloudFilterParams{};
  params.edge_side_min_contrast = std::nan("");
  EXPECT_TRUE(test::throwsNaming([&] { params.validate(); }, "edge_side_min_contrast"));
}

TEST(CloudFilter, RefusesCloudsAndStatusesThatDoNotMatch) {
  Grid g = tiltedPlane();
  cv::Mat small(10, 10, CV_8UC1, cv::Scalar(0));
  EXPECT_THROW(filterCloud(g.cloud, small, CloudFilterParams{}), core::Error);
  cv::Mat wide_type(80, 100, CV_16UC1, cv::Scalar(0));
  EXPECT_THROW(filterCloud(g.cloud, wide_type, CloudFilterParams{}), core::Error);
  io::PointCloud unorganized = g.cloud;
  unorganized.width = unorganized.height = 0;
  EXPECT_THROW(filterCloud(unorganized, g.status, CloudFilterParams{}), core::Error);
  const cv::Mat small_noise(10, 10, CV_32FC1, cv::Scalar(0.5f));
  EXPECT_THROW(filterCloud(g.cloud, g.status, CloudFilterParams{}, {small_noise, cv::Mat()}), core::Error);
}

std::string paramsError(const CloudFilterParams& params) {
  return binpick::test::thrownMessage([&] { params.validate(); });
}

TEST(CloudFilter, RefusesBadParamsNamingTheField) {
  CloudFilterParams params;
  params.min_depth = -0.1;
  EXPECT_NE(paramsError(params).find("min_depth"), std::string::npos);
  params = {};
  params.max_depth = 0.0;
  EXPECT_NE(paramsError(params).find("max_depth"), std::string::npos);
  params = {};
  params.crop = Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, NAN), Eigen::Vector3d(1, 1, 1));
  EXPECT_NE(paramsError(params).find("crop"), std::string::npos);
  params = {};
  params.speckle_max_step = 0.0;
  EXPECT_NE(paramsError(params).find("speckle_max_step"), std::string::npos);
  params = {};
  params.speckle_min_pixels = -1;
  EXPECT_NE(paramsError(params).find("speckle_min_pixels"), std::string::npos);
  params = {};
  params.median_reach = -1.0;
  EXPECT_NE(paramsError(params).find("median_reach"), std::string::npos);
  params = {};
  params.median_max_pull = 0.0;
  EXPECT_NE(paramsError(params).find("median_max_pull"), std::string::npos);
  params = {};
  params.median_max_intensity = -0.1;
  EXPECT_NE(paramsError(params).find("median_max_intensity"), std::string::npos);
  params = {};
  params.median_min_noise = std::nan("");
  EXPECT_NE(paramsError(params).find("median_min_noise"), std::string::npos);
  params = {};
  params.median_lone_max_noise = -0.5;
  EXPECT_NE(paramsError(params).find("median_lone_max_noise"), std::string::npos);
  params = {};
  params.max_depth = std::numeric_limits<double>::infinity();  // keeps everything: allowed
  EXPECT_EQ(paramsError(params), "");
}

}  // namespace
}  // namespace binpick::reconstruction
