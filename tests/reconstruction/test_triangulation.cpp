// Triangulation against the virtual cell's truth: a perfect decoding of a pile (every camera
// pixel given the exact projector pixel its surface point projects to) must give that point back.
#include "binpick/reconstruction/triangulation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/pile.hpp"
#include "thrown_message.hpp"

namespace binpick::reconstruction {
namespace {

constexpr auto kValid = static_cast<uint8_t>(PixelStatus::Valid);

io::RigCalibration withoutDistortion(io::RigCalibration rig) {
  rig.camera.distortion = {};
  rig.projector.distortion = {};
  return rig;
}

// A small pile seen by a half-resolution camera (the projector keeps its full resolution):
// generated once per lens setting and shared by the tests.
const simulation::PileScene& pile(bool distortion) {
  static std::map<bool, simulation::PileScene> cache;
  auto found = cache.find(distortion);
  if (found != cache.end()) return found->second;
  simulation::PileParams params;
  params.objects = 5;
  params.seed = 11;
  params.rig.camera = params.rig.camera.scaled(0.5);
  if (!distortion) params.rig = withoutDistortion(params.rig);
  return cache.emplace(distortion, simulation::generatePile(simulation::makePart("clamp").mesh, params)).first->second;
}

const Eigen::Vector3f& exactPoint(const simulation::PileScene& scene, std::size_t pixel) {
  return scene.exact_cloud.points[pixel];
}

// Where a camera-frame point lands in the projector image; false behind the projector.
bool projectorPixel(const io::RigCalibration& rig, const Eigen::Vector3d& point, Eigen::Vector2d& pixel) {
  const Eigen::Vector3d in_projector = rig.T_projector_camera * point;
  if (!(in_projector.z() > 0.0)) return false;
  pixel = rig.projector.project(in_projector);
  return true;
}

bool insideImage(const io::LensIntrinsics& lens, const Eigen::Vector2d& pixel) {
  return pixel.x() >= -0.5 && pixel.x() < lens.width - 0.5 && pixel.y() >= -0.5 && pixel.y() < lens.height - 0.5;
}

// What an ideal decoder reports: the exact projector pixel of every surface point that projects
// into the projector's image (lit or in shadow alike: triangulation does not care), Unlit
// elsewhere.
DecodedCapture perfectDecoding(const simulation::PileScene& scene, bool rows, const io::RigCalibration& rig) {
  const io::LensIntrinsics& camera = rig.camera;
  DecodedCapture decoded;
  decoded.width = camera.width;
  decoded.height = camera.height;
  decoded.column = cv::Mat(camera.height, camera.width, CV_32FC1, cv::Scalar(NAN));
  if (rows) decoded.row = cv::Mat(camera.height, camera.width, CV_32FC1, cv::Scalar(NAN));
  decoded.status = cv::Mat(camera.height, camera.width, CV_8UC1, cv::Scalar(static_cast<int>(PixelStatus::Unlit)));
  for (std::size_t i = 0; i < scene.exact_cloud.size(); ++i) {
    const Eigen::Vector3f& point = exactPoint(scene, i);
    Eigen::Vector2d pixel;
    if (!point.allFinite() || !projectorPixel(rig, point.cast<double>(), pixel) || !insideImage(rig.projector, pixel)) {
      continue;
    }
    decoded.column.ptr<float>(0)[i] = static_cast<float>(pixel.x());
    if (rows) decoded.row.ptr<float>(0)[i] = static_cast<float>(pixel.y());
    decoded.status.ptr<uint8_t>(0)[i] = kValid;
  }
  return decoded;
}

DecodedCapture perfectDecoding(const simulation::PileScene& scene, bool rows) {
  return perfectDecoding(scene, rows, scene.rig);
}

uint8_t statusAt(const cv::Mat& status, std::size_t pixel) { return status.ptr<uint8_t>(0)[pixel]; }
float& at(cv::Mat& image, std::size_t pixel) { return image.ptr<float>(0)[pixel]; }

TriangulationParams singleThreaded() {
  TriangulationParams params;
  params.threads = 1;
  return params;
}

struct Comparison {
  std::size_t inputs = 0;       // Valid pixels of the decoding
  std::size_t valid = 0;        // of those, Valid after triangulation
  double max_error = 0.0;       // metres, over the valid ones
  std::size_t others_kept = 0;  // non-Valid input pixels left NaN with their status
  std::size_t others = 0;
};

Comparison compare(const simulation::PileScene& scene, const DecodedCapture& decoded, const TriangulatedCloud& result) {
  Comparison c;
  for (std::size_t i = 0; i < scene.exact_cloud.size(); ++i) {
    const Eigen::Vector3f& point = result.cloud.points[i];
    if (statusAt(decoded.status, i) != kValid) {
      ++c.others;
      const bool kept = statusAt(result.status, i) == statusAt(decoded.status, i);
      if (kept && point.array().isNaN().all()) ++c.others_kept;
      continue;
    }
    ++c.inputs;
    if (statusAt(result.status, i) != kValid) continue;
    ++c.valid;
    c.max_error = std::max(c.max_error, static_cast<double>((point - exactPoint(scene, i)).norm()));
  }
  return c;
}

void expectExactReconstruction(bool distortion, bool rows) {
  SCOPED_TRACE(std::string(distortion ? "with" : "without") + " distortion, " +
               (rows ? "columns and rows" : "columns only"));
  const simulation::PileScene& scene = pile(distortion);
  const DecodedCapture decoded = perfectDecoding(scene, rows);
  const TriangulatedCloud result = Triangulator(scene.rig).triangulate(decoded);
  EXPECT_EQ(result.cloud.width, scene.rig.camera.width);
  EXPECT_EQ(result.cloud.height, scene.rig.camera.height);
  EXPECT_TRUE(result.cloud.isOrganized());
  EXPECT_FALSE(result.cloud.hasNormals());
  const Comparison c = compare(scene, decoded, result);
  EXPECT_GT(c.inputs, 50000u);
  EXPECT_EQ(c.valid, c.inputs);
  EXPECT_LT(c.max_error, 1e-5);
  EXPECT_EQ(c.others_kept, c.others);
}

TEST(Triangulation, PerfectColumnsAndRowsGiveTheSurfaceBack) {
  expectExactReconstruction(true, true);
  expectExactReconstruction(false, true);
}

TEST(Triangulation, PerfectColumnsAloneGiveTheSurfaceBackThroughCurvedLightPlanes) {
  expectExactReconstruction(true, false);
  expectExactReconstruction(false, false);
}

// Another placement: the projector to the camera's left and above it, rolled, and looking down
// at the scene; a tilted plane with a bump as the surface (no pile needed).
TEST(Triangulation, PerfectDecodingWorksForAnyProjectorPlacement) {
  simulation::PileScene scene;
  scene.rig = simulation::makeVirtualRig();
  scene.rig.camera = scene.rig.camera.scaled(0.25);
  scene.rig.projector.distortion = {-0.06, 0.03, 0.001, -0.0005, 0.0};
  Eigen::Isometry3d T_camera_projector = Eigen::Isometry3d::Identity();
  T_camera_projector.translation() = Eigen::Vector3d(-0.22, -0.08, 0.03);
  T_camera_projector.linear() =
      (Eigen::AngleAxisd(0.25, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(-0.09, Eigen::Vector3d::UnitX()) *
       Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitZ()))
          .matrix();
  scene.rig.T_projector_camera = T_camera_projector.inverse();
  const io::LensIntrinsics& camera = scene.rig.camera;
  scene.exact_cloud.width = camera.width;
  scene.exact_cloud.height = camera.height;
  for (int y = 0; y < camera.height; ++y) {
    for (int x = 0; x < camera.width; ++x) {
      const Eigen::Vector3d ray = camera.rayThroughPixel({static_cast<double>(x), static_cast<double>(y)});
      const Eigen::Vector3d direction = ray / ray.z();
      const double bump = 0.05 * std::exp(-direction.head<2>().squaredNorm() / 0.02);
      const double z = 0.8 + 0.15 * direction.x() - 0.1 * direction.y() - bump;
      scene.exact_cloud.points.push_back((z * direction).cast<float>());
    }
  }
  for (bool rows : {true, false}) {
    SCOPED_TRACE(rows ? "columns and rows" : "columns only");
    const DecodedCapture decoded = perfectDecoding(scene, rows);
    const Comparison c = compare(scene, decoded, Triangulator(scene.rig).triangulate(decoded));
    EXPECT_GT(c.inputs, 10000u);
    EXPECT_EQ(c.valid, c.inputs);
    EXPECT_LT(c.max_error, 1e-5);
  }
}

TEST(Triangulation, RowsOffTheEpipolarCurveAreInconsistent) {
  const simulation::PileScene& scene = pile(true);
  TriangulationParams params;
  params.column_when_row_inconsistent = false;
  params.max_calibration_residual = 0.0;  // a shift of every row would be the calibration's residual
  const Triangulator triangulator(scene.rig, params);
  const DecodedCapture exact = perfectDecoding(scene, true);
  const TriangulatedCloud truth = triangulator.triangulate(exact);
  for (float shift : {3.0f, -3.0f, 1.0f}) {
    SCOPED_TRACE("row shifted by " + std::to_string(shift));
    DecodedCapture decoded = exact;
    decoded.row = cv::Mat();  // not into the pixels `exact` shares
    decoded.row = exact.row + shift;
    const TriangulatedCloud result = triangulator.triangulate(decoded);
    std::size_t inputs = 0, inconsistent = 0, valid = 0;
    double max_moved = 0.0;
    for (std::size_t i = 0; i < result.cloud.size(); ++i) {
      if (statusAt(decoded.status, i) != kValid) continue;
      ++inputs;
      const uint8_t status = statusAt(result.status, i);
      if (status == static_cast<uint8_t>(PixelStatus::Inconsistent)) ++inconsistent;
      if (status != kValid) continue;
      ++valid;
      max_moved = std::max(max_moved, static_cast<double>((result.cloud.points[i] - truth.cloud.points[i]).norm()));
    }
    if (std::abs(shift) > 1.5f) {
      EXPECT_EQ(inconsistent, inputs);
    } else {
      // Within the tolerance the point stays; with a horizontal baseline the row carries little
      // depth, so it hardly moves.
      EXPECT_EQ(valid, inputs);
      EXPECT_LT(max_moved, 0.002);
    }
  }
}

// A calibration slightly off shifts every decoded row by an offset that varies smoothly over the
// image (here from -4 to +4 px across it): the triangulator follows that residual and keeps the
// pixels, while a patch misdecoded 5 px off its surroundings stands out as Inconsistent.
TEST(Triangulation, ACalibrationsSmoothResidualIsFollowedAndMisdecodedRowsStillStandOut) {
  const simulation::PileScene& scene = pile(true);
  const Triangulator triangulator(scene.rig);
  const DecodedCapture exact = perfectDecoding(scene, true);
  DecodedCapture decoded = exact;
  decoded.row = exact.row.clone();
  const cv::Rect misdecoded(exact.width / 2, exact.height / 2, 12, 12);
  for (int y = 0; y < exact.height; ++y) {
    for (int x = 0; x < exact.width; ++x) {
      decoded.row.at<float>(y, x) += -4.0f + 8.0f * static_cast<float>(x) / static_cast<float>(exact.width);
      if (misdecoded.contains({x, y})) decoded.row.at<float>(y, x) += 5.0f;
    }
  }
  const TriangulatedCloud result = triangulator.triangulate(decoded);
  std::size_t inputs = 0, kept = 0, patch_inputs = 0, patch_inconsistent = 0;
  for (int y = 0; y < exact.height; ++y) {
    for (int x = 0; x < exact.width; ++x) {
      if (exact.status.at<uint8_t>(y, x) != kValid) continue;
      const uint8_t status = result.status.at<uint8_t>(y, x);
      if (misdecoded.contains({x, y})) {
        ++patch_inputs;
        patch_inconsistent += status == static_cast<uint8_t>(PixelStatus::Inconsistent) ? 1 : 0;
      } else {
        ++inputs;
        kept += status == kValid ? 1 : 0;
      }
    }
  }
  ASSERT_GT(patch_inputs, 50u) << "the patch must fall on the pile";
  EXPECT_GT(static_cast<double>(kept) / inputs, 0.99);
  EXPECT_GT(static_cast<double>(patch_inconsistent) / patch_inputs, 0.9);
  // The pile covers the middle of the image: the field's largest offset there, not the border's.
  EXPECT_GT(result.calibration_fit.largest_residual_px, 2.0);
  EXPECT_LT(result.calibration_fit.largest_residual_px, 4.2);

  TriangulationParams absolute;
  absolute.max_calibration_residual = 0.0;
  const TriangulatedCloud judged_absolutely = Triangulator(scene.rig, absolute).triangulate(decoded);
  EXPECT_GT(countStatuses(judged_absolutely.status)[static_cast<std::size_t>(PixelStatus::Inconsistent)], inputs / 3);
}

// The depth a projector pixel spans along the epipolar line is what moving the decoded position
// one pixel along it does to the point.
TEST(Triangulation, DepthPerProjectorPixelIsTheDepthOnePixelAlongTheLineMoves) {
  const simulation::PileScene& scene = pile(false);
  const Triangulator triangulator(scene.rig);
  const DecodedCapture exact = perfectDecoding(scene, false);
  DecodedCapture moved = exact;
  moved.column = cv::Mat();  // not into the pixels `exact` shares
  moved.column = exact.column + 1.0;  // columns only: the line runs across the columns
  const TriangulatedCloud before = triangulator.triangulate(exact);
  const TriangulatedCloud after = triangulator.triangulate(moved);
  std::size_t checked = 0;
  for (std::size_t i = 0; i < before.cloud.size(); i += 97) {
    const float z0 = before.cloud.points[i].z(), z1 = after.cloud.points[i].z();
    if (!std::isfinite(z0) || !std::isfinite(z1)) continue;
    const float predicted = before.depth_per_projector_px.ptr<float>(0)[i];
    // The column's light crosses the line at an angle: one column is at least one pixel along it.
    EXPECT_NEAR(std::abs(z1 - z0), predicted, 0.15 * predicted) << i;
    ++checked;
  }
  EXPECT_GT(checked, 100u);
}

// The decoder keeps the column of a pixel whose row failed (row NaN): such pixels are solved from
// the column's light alone, as in a capture without rows.
TEST(Triangulation, PixelsWhoseRowIsMissingAreSolvedFromTheirColumn) {
  const simulation::PileScene& scene = pile(true);
  const DecodedCapture exact = perfectDecoding(scene, true);
  DecodedCapture decoded = exact;
  decoded.row = exact.row.clone();
  std::size_t dropped = 0;
  for (std::size_t i = 0; i < scene.exact_cloud.size(); i += 3) {
    if (statusAt(decoded.status, i) != kValid) continue;
    at(decoded.row, i) = NAN;
    ++dropped;
  }
  ASSERT_GT(dropped, 10000u);
  const Comparison c = compare(scene, decoded, Triangulator(scene.rig).triangulate(decoded));
  EXPECT_EQ(c.valid, c.inputs);
  EXPECT_LT(c.max_error, 0.0005);  // metres
}

// A row off the epipolar curve is a wrong row; the column still names the light plane.
TEST(Triangulation, PixelsWhoseRowIsInconsistentAreSolvedFromTheirColumn) {
  const simulation::PileScene& scene = pile(true);
  const DecodedCapture exact = perfectDecoding(scene, true);
  DecodedCapture decoded = exact;
  decoded.row = cv::Mat();  // not into the pixels `exact` shares
  decoded.row = exact.row + 4.0f;
  TriangulationParams params;
  params.column_when_row_inconsistent = true;
  const Comparison c = compare(scene, decoded, Triangulator(scene.rig, params).triangulate(decoded));
  EXPECT_GT(c.inputs, 50000u);
  EXPECT_EQ(c.valid, c.inputs);
  EXPECT_LT(c.max_error, 0.0005);
}

TEST(Triangulation, KeepsTheDecodersVerdictOnPixelsItRejected) {
  const simulation::PileScene& scene = pile(true);
  DecodedCapture decoded = perfectDecoding(scene, true);
  const PixelStatus rejected[] = {PixelStatus::Unlit, PixelStatus::Saturated, PixelStatus::UncertainCode,
                                  PixelStatus::PhaseMismatch, PixelStatus::CodeOutOfRange};
  // Their coordinates stay finite: only the status says they are not to be used.
  std::size_t marked = 0;
  for (std::size_t i = 0; i < scene.exact_cloud.size(); i += 7) {
    if (statusAt(decoded.status, i) != kValid) continue;
    decoded.status.ptr<uint8_t>(0)[i] = static_cast<uint8_t>(rejected[marked++ % 5]);
  }
  const TriangulatedCloud result = Triangulator(scene.rig).triangulate(decoded);
  const Comparison c = compare(scene, decoded, result);
  EXPECT_GT(marked, 5000u);
  EXPECT_EQ(c.others_kept, c.others);
  EXPECT_EQ(c.valid, c.inputs);
}

// Depth sensitivity to the column from the lens model alone: how far along the ray the point
// must move for its projection to move one projector column.
double depthPerColumn(const io::RigCalibration& rig, const Eigen::Vector3d& point) {
  const Eigen::Vector3d direction = point / point.z();
  constexpr double kStep = 1e-4;  // metres
  Eigen::Vector2d near_pixel, far_pixel;
  projectorPixel(rig, (point.z() - kStep) * direction, near_pixel);
  projectorPixel(rig, (point.z() + kStep) * direction, far_pixel);
  return 2.0 * kStep / std::abs(far_pixel.x() - near_pixel.x());
}

TEST(Triangulation, ColumnNoiseGivesTheDepthErrorTheGeometryPredicts) {
  const simulation::PileScene& scene = pile(true);
  DecodedCapture decoded = perfectDecoding(scene, false);
  constexpr double kNoise = 0.1;  // projector pixels
  std::mt19937 random(3);
  std::normal_distribution<double> noise(0.0, kNoise);
  for (std::size_t i = 0; i < scene.exact_cloud.size(); ++i) {
    at(decoded.column, i) += static_cast<float>(noise(random));
  }
  const TriangulatedCloud result = Triangulator(scene.rig).triangulate(decoded);
  double sum = 0.0, sum_sq = 0.0, predicted_sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < scene.exact_cloud.size(); ++i) {
    if (statusAt(result.status, i) != kValid) continue;
    const Eigen::Vector3d truth = exactPoint(scene, i).cast<double>();
    const double sigma = kNoise * depthPerColumn(scene.rig, truth);
    const double normalised = (result.cloud.points[i].z() - truth.z()) / sigma;
    sum += normalised;
    sum_sq += normalised * normalised;
    predicted_sum += sigma;
    ++count;
  }
  ASSERT_GT(count, 50000u);
  const double n = static_cast<double>(count);
  // Errors in units of the predicted standard deviation: unbiased, of unit spread.
  EXPECT_NEAR(sum / n, 0.0, 0.05);
  EXPECT_NEAR(std::sqrt(sum_sq / n), 1.0, 0.05);
  // The order of magnitude: z^2 / (f b) * noise = 0.9^2 / (1560 * 0.25) * 0.1 = 0.2 mm.
  EXPECT_GT(predicted_sum / n, 1e-4);
  EXPECT_LT(predicted_sum / n, 4e-4);
}

// Beyond the vanishing point of a camera ray (where its points project from infinitely far),
// projector columns light the ray only behind the camera.
TEST(Triangulation, ColumnsBeyondTheRaysVanishingPointGiveNoIntersection) {
  const simulation::PileScene& scene = pile(true);
  const io::LensIntrinsics& camera = scene.rig.camera;
  for (bool rows : {true, false}) {
    SCOPED_TRACE(rows ? "columns and rows" : "columns only");
    DecodedCapture decoded = perfectDecoding(scene, rows);
    std::size_t moved = 0;
    for (std::size_t i = 0; i < scene.exact_cloud.size(); ++i) {
      if (statusAt(decoded.status, i) != kValid) continue;
      const Eigen::Vector2d pixel(static_cast<double>(i % camera.width), static_cast<double>(i / camera.width));
      const Eigen::Vector3d far_away = scene.rig.T_projector_camera.linear() * camera.rayThroughPixel(pixel);
      const Eigen::Vector2d vanishing = scene.rig.projector.project(far_away);
      const bool row_inside = vanishing.y() >= 0.0 && vanishing.y() <= scene.rig.projector.height - 1;
      if (vanishing.x() + 40.0 > scene.rig.projector.width - 1 || !row_inside) {
        decoded.status.ptr<uint8_t>(0)[i] = static_cast<uint8_t>(PixelStatus::Unlit);
        continue;
      }
      at(decoded.column, i) = static_cast<float>(vanishing.x() + 40.0);
      if (rows) at(decoded.row, i) = static_cast<float>(vanishing.y());
      ++moved;
    }
    const TriangulatedCloud result = Triangulator(scene.rig).triangulate(decoded);
    const StatusCounts counts = countStatuses(result.status);
    EXPECT_GT(moved, 10000u);
    EXPECT_EQ(counts[static_cast<std::size_t>(PixelStatus::NoIntersection)], moved);
  }
}

// Where a ray's epipolar plane crosses a column's light outside the projector's image (here: a
// projector whose image is cut to its middle 400 rows), that light cannot reach the ray.
TEST(Triangulation, ColumnOnlyRaysOutsideTheProjectorsRowsGiveNoIntersection) {
  const simulation::PileScene& scene = pile(true);
  io::RigCalibration band = scene.rig;
  band.projector.height = 400;
  band.projector.cy -= 200.0;
  DecodedCapture decoded = perfectDecoding(scene, false, band);
  std::size_t outside = 0, inside = 0;
  for (std::size_t i = 0; i < scene.exact_cloud.size(); ++i) {
    Eigen::Vector2d pixel;
    const Eigen::Vector3f& point = exactPoint(scene, i);
    if (!point.allFinite() || !projectorPixel(band, point.cast<double>(), pixel)) continue;
    if (statusAt(decoded.status, i) == kValid) ++inside;
    const bool rows_outside = pixel.y() < -20.0 || pixel.y() > band.projector.height + 20.0;
    if (!rows_outside || pixel.x() < 0.0 || pixel.x() > band.projector.width - 1) continue;
    at(decoded.column, i) = static_cast<float>(pixel.x());
    decoded.status.ptr<uint8_t>(0)[i] = kValid;
    ++outside;
  }
  const TriangulatedCloud result = Triangulator(band).triangulate(decoded);
  const StatusCounts counts = countStatuses(result.status);
  EXPECT_GT(outside, 10000u);
  EXPECT_EQ(counts[static_cast<std::size_t>(PixelStatus::NoIntersection)], outside);
  EXPECT_EQ(counts[static_cast<std::size_t>(PixelStatus::Valid)], inside);
}

TEST(Triangulation, CoordinatesOutsideTheProjectorImageAreOutOfRange) {
  const simulation::PileScene& scene = pile(true);
  for (bool rows : {true, false}) {
    SCOPED_TRACE(rows ? "columns and rows" : "columns only");
    DecodedCapture decoded = perfectDecoding(scene, rows);
    std::size_t changed = 0;
    for (std::size_t i = 0; i < scene.exact_cloud.size(); i += 3) {
      if (statusAt(decoded.status, i) != kValid) continue;
      switch (changed++ % 3) {
        case 0: at(decoded.column, i) = scene.rig.projector.width + 20.0f; break;
        case 1: at(decoded.column, i) = NAN; break;
        default:
          if (rows)
            at(decoded.row, i) = -30.0f;
          else
            at(decoded.column, i) = -30.0f;
      }
    }
    const TriangulatedCloud result = Triangulator(scene.rig).triangulate(decoded);
    const StatusCounts counts = countStatuses(result.status);
    EXPECT_GT(changed, 10000u);
    EXPECT_EQ(counts[static_cast<std::size_t>(PixelStatus::CodeOutOfRange)], changed);
  }
}

TEST(Triangulation, ResultsDoNotDependOnTheThreadCount) {
  const simulation::PileScene& scene = pile(true);
  DecodedCapture decoded = perfectDecoding(scene, true);
  std::mt19937 random(5);
  std::normal_distribution<float> noise(0.0f, 0.5f);
  for (std::size_t i = 0; i < scene.exact_cloud.size(); ++i) {
    at(decoded.column, i) += noise(random);
    at(decoded.row, i) += noise(random);
  }
  for (bool rows : {true, false}) {
    SCOPED_TRACE(rows ? "columns and rows" : "columns only");
    DecodedCapture input = decoded;
    if (!rows) input.row = cv::Mat();
    TriangulationParams two = singleThreaded();
    two.threads = 2;
    const TriangulatedCloud a = Triangulator(scene.rig, singleThreaded()).triangulate(input);
    const TriangulatedCloud b = Triangulator(scene.rig, two).triangulate(input);
    ASSERT_EQ(a.cloud.size(), b.cloud.size());
    EXPECT_EQ(std::memcmp(a.cloud.points.data(), b.cloud.points.data(), a.cloud.size() * sizeof(Eigen::Vector3f)), 0);
    EXPECT_EQ(cv::countNonZero(a.status != b.status), 0);
  }
}

std::string triangulateError(const Triangulator& triangulator, const DecodedCapture& decoded) {
  return binpick::test::thrownMessage([&] { triangulator.triangulate(decoded); });
}

TEST(Triangulation, RefusesADecodingOfAnotherSizeOrType) {
  const simulation::PileScene& scene = pile(true);
  const Triangulator triangulator(scene.rig);
  const DecodedCapture good = perfectDecoding(scene, true);
  DecodedCapture decoded = good;
  decoded.width = good.width / 2;
  EXPECT_NE(triangulateError(triangulator, decoded).find("camera is"), std::string::npos);
  decoded = good;
  decoded.column = cv::Mat(good.height, good.width, CV_64FC1, cv::Scalar(0));
  EXPECT_NE(triangulateError(triangulator, decoded).find("decoded.column"), std::string::npos);
  decoded = good;
  decoded.row = cv::Mat(good.height - 1, good.width, CV_32FC1, cv::Scalar(0));
  EXPECT_NE(triangulateError(triangulator, decoded).find("decoded.row"), std::string::npos);
  decoded = good;
  decoded.status = cv::Mat();
  EXPECT_NE(triangulateError(triangulator, decoded).find("decoded.status"), std::string::npos);
}

TEST(Triangulation, RefusesBadParamsNamingTheField) {
  const io::RigCalibration rig = simulation::makeVirtualRig();
  for (double bad : {0.0, -1.0, std::nan("")}) {
    TriangulationParams params;
    params.max_epipolar_error = bad;
    EXPECT_THROW(params.validate(), core::Error);
    try {
      Triangulator(rig, params);
      ADD_FAILURE() << "accepted max_epipolar_error " << bad;
    } catch (const core::Error& error) {
      EXPECT_NE(std::string(error.what()).find("max_epipolar_error"), std::string::npos);
    }
  }
  TriangulationParams params;
  params.threads = -1;
  EXPECT_THROW(params.validate(), core::Error);
}

}  // namespace
}  // namespace binpick::reconstruction
