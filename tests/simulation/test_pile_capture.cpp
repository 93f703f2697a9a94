// The rendered pattern images of a pile agree with its exact geometry: shadows where the projector
// cannot reach, and Gray-code bits that spell the projector column the exact point projects to.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "binpick/reconstruction/pattern_set.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/pile.hpp"

namespace binpick::simulation {
namespace {

namespace rc = binpick::reconstruction;

struct RenderedPile {
  PileParams params;
  PileScene scene;
  io::PatternSetSpec patterns;
  std::vector<cv::Mat> images;
};

// Half-resolution camera, column codes only: what these checks need, at a fraction of the time.
const RenderedPile& renderedPile() {
  static const RenderedPile pile = [] {
    RenderedPile p;
    p.params.objects = 12;
    p.params.seed = 21;
    p.params.rig.camera = p.params.rig.camera.scaled(0.5);
    p.patterns.projector_width = p.params.rig.projector.width;
    p.patterns.projector_height = p.params.rig.projector.height;
    p.patterns.row_codes = false;
    p.patterns.phase_steps = 0;
    const io::TriangleMesh part = makePart("clamp").mesh;
    p.scene = generatePile(part, p.params);
    PhotometryParams photometry;
    photometry.seed = 5;
    p.images = renderPileImages(part, p.scene, p.params, p.patterns, photometry);
    return p;
  }();
  return pile;
}

int value(const cv::Mat& image, std::size_t index) { return image.ptr<uint8_t>(0)[index]; }

TEST(PileCapture, ShadowsInTheImagesAreWhereTheGeometryHasThem) {
  const RenderedPile& p = renderedPile();
  const cv::Mat& white = p.images[0];
  const cv::Mat& black = p.images[1];
  const Eigen::Vector3f projector_centre = p.scene.rig.T_projector_camera.inverse().translation().cast<float>();
  int lit = 0, lit_bright = 0, shadowed = 0, shadowed_dark = 0;
  for (std::size_t i = 0; i < p.scene.instance.size(); ++i) {
    const Eigen::Vector3f point = p.scene.exact_cloud.points[i];
    const Eigen::Vector3f normal = p.scene.exact_cloud.normals[i];
    if (!point.allFinite()) continue;  // nothing there
    // Surfaces facing both devices squarely: their light does not depend on fine angles, and no
    // viewing-angle limit removes them from the measured cloud.
    const float to_camera = normal.dot(-point.normalized());
    const float to_projector = normal.dot((projector_centre - point).normalized());
    if (to_camera < 0.5f || to_projector < 0.5f) continue;
    const int contrast = value(white, i) - value(black, i);
    if (p.scene.cloud.points[i].allFinite()) {
      ++lit;
      lit_bright += contrast > 20;
    } else {  // facing the projector yet unmeasured: something casts a shadow on it
      ++shadowed;
      shadowed_dark += contrast < 15;  // only indirect light and noise
    }
  }
  ASSERT_GT(lit, 10000);
  ASSERT_GT(shadowed, 100);
  EXPECT_GT(static_cast<double>(lit_bright) / lit, 0.99);
  EXPECT_GT(static_cast<double>(shadowed_dark) / shadowed, 0.97);
}

TEST(PileCapture, GrayCodeSpellsTheColumnTheExactPointProjectsTo) {
  const RenderedPile& p = renderedPile();
  const auto sequence = rc::patternSequence(p.patterns);
  const int bits = rc::grayCodeBits(p.patterns.projector_width);
  int checked = 0, exact = 0, within_one = 0;
  for (std::size_t i = 0; i < p.scene.instance.size(); i += 7) {
    if (!p.scene.cloud.points[i].allFinite()) continue;
    const Eigen::Vector3d point = p.scene.exact_cloud.points[i].cast<double>();
    const Eigen::Vector2d projector = p.scene.rig.projector.project(p.scene.rig.T_projector_camera * point);
    const int truth = static_cast<int>(std::lround(projector.x()));
    unsigned code = 0;
    for (int b = 0; b < bits; ++b) {
      // Images 2 + 2b and 3 + 2b: bit b and its inverse (after white and black).
      ASSERT_EQ(sequence[2 + 2 * b].kind, rc::PatternKind::GrayBit);
      const bool on = value(p.images[2 + 2 * b], i) > value(p.images[3 + 2 * b], i);
      code = (code << 1) | (on ? 1u : 0u);
    }
    const int decoded = static_cast<int>(rc::grayDecode(code));
    ++checked;
    exact += decoded == truth;
    within_one += std::abs(decoded - truth) <= 1;
  }
  ASSERT_GT(checked, 1000);
  // Pixels whose point lies on a stripe edge may go either way; the rest must be exact.
  EXPECT_GT(static_cast<double>(exact) / checked, 0.85);
  EXPECT_GT(static_cast<double>(within_one) / checked, 0.98);
}

TEST(PileCapture, SameSeedSameImages) {
  const RenderedPile& p = renderedPile();
  PhotometryParams photometry;
  photometry.seed = 5;
  const auto again = renderPileImages(makePart("clamp").mesh, p.scene, p.params, p.patterns, photometry);
  ASSERT_EQ(again.size(), p.images.size());
  for (std::size_t k = 0; k < again.size(); ++k) {
    EXPECT_EQ(cv::norm(again[k], p.images[k], cv::NORM_INF), 0.0) << "image " << k;
  }
}

// Whether the truth has a depth edge (another object, or depths 3 mm apart) within `reach` pixels.
bool nearDepthEdge(const PileScene& scene, int x, int y, int reach) {
  const int w = scene.rig.camera.width, h = scene.rig.camera.height;
  const auto at = [&](int u, int v) { return static_cast<std::size_t>(v) * w + u; };
  for (int v = std::max(0, y - reach); v <= std::min(h - 2, y + reach); ++v) {
    for (int u = std::max(0, x - reach); u <= std::min(w - 2, x + reach); ++u) {
      for (const std::size_t j : {at(u + 1, v), at(u, v + 1)}) {
        const std::size_t i = at(u, v);
        if (scene.instance[i] != scene.instance[j] || !(std::fabs(scene.depth[i] - scene.depth[j]) <= 0.003f)) {
          return true;
        }
      }
    }
  }
  return false;
}

// Several rays over the pixels at depth edges against one per pixel: the images differ there, at
// many pixels (shadowed ones beside a lit edge get some of its light), and nowhere else (the
// noise is keyed by pixel, so the rest is the same to the bit).
TEST(PileCapture, MixedPixelsChangeTheImagesAtDepthEdgesOnly) {
  const RenderedPile& p = renderedPile();
  PhotometryParams photometry;
  photometry.seed = 5;
  photometry.mixed_pixel_samples = 3;
  const cv::Mat mixed = renderPileImages(makePart("clamp").mesh, p.scene, p.params, p.patterns, photometry)[0];
  const cv::Mat& one_ray = p.images[0];  // white
  int changed = 0, changed_off_edges = 0, shadowed_brighter = 0;
  for (int y = 0; y < mixed.rows; ++y) {
    for (int x = 0; x < mixed.cols; ++x) {
      const int difference = mixed.at<uint8_t>(y, x) - one_ray.at<uint8_t>(y, x);
      if (difference == 0) continue;
      ++changed;
      changed_off_edges += nearDepthEdge(p.scene, x, y, 2) ? 0 : 1;
      const std::size_t i = static_cast<std::size_t>(y) * mixed.cols + x;
      shadowed_brighter += p.scene.exact_cloud.points[i].allFinite() && !p.scene.cloud.points[i].allFinite() &&
                           difference > 20;
    }
  }
  EXPECT_GT(changed, 500);
  EXPECT_GT(shadowed_brighter, 50);
  EXPECT_EQ(changed_off_edges, 0);
}

}  // namespace
}  // namespace binpick::simulation
