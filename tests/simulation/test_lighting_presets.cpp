// The virtual cell's named photometry presets: "clean" is the default, "harsh" renders dark
// glossy parts whose highlights clip, and an unknown name is refused with the known ones.
#include "sensor/lighting_presets.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/pile.hpp"
#include "thrown_message.hpp"

namespace binpick::simulation {
namespace {

TEST(PhotometryPreset, CleanIsTheDefaultPhotometry) {
  const PhotometryParams clean = photometryPreset("clean");
  const PhotometryParams defaults;
  EXPECT_EQ(clean.projector_white, defaults.projector_white);
  EXPECT_EQ(clean.albedo_scale, 1.0);
  EXPECT_EQ(clean.global_light, defaults.global_light);
  EXPECT_EQ(clean.read_noise, defaults.read_noise);
  EXPECT_EQ(clean.specular, defaults.specular);
}

TEST(PhotometryPreset, HarshIsDarkGlossyNoisyAndIndirect) {
  const PhotometryParams harsh = photometryPreset("harsh");
  EXPECT_NO_THROW(harsh.validate());
  EXPECT_LT(harsh.albedo_scale, 0.5);
  EXPECT_NEAR(harsh.global_light, 0.35, 1e-12);
  EXPECT_NEAR(harsh.read_noise, 3.0, 1e-12);
  EXPECT_GT(harsh.specular, PhotometryParams{}.specular);
}

TEST(PhotometryPreset, UnknownNameIsRefusedWithTheKnownOnes) {
  const std::string message = test::thrownMessage([] { photometryPreset("dim"); });
  EXPECT_NE(message.find("'dim'"), std::string::npos) << message;
  EXPECT_NE(message.find("clean"), std::string::npos) << message;
  EXPECT_NE(message.find("harsh"), std::string::npos) << message;
  EXPECT_EQ(photometryPresetNames(), (std::vector<std::string>{"clean", "harsh"}));
}

TEST(PhotometryParams, NegativeAlbedoScaleIsRefused) {
  PhotometryParams params;
  params.albedo_scale = -0.1;
  EXPECT_NE(test::thrownMessage([&] { params.validate(); }).find("albedo_scale"), std::string::npos);
}

// The white image of one small pile under both presets.
struct WhiteImages {
  PileScene scene;
  cv::Mat clean, harsh;
};

const WhiteImages& whiteImages() {
  static const WhiteImages images = [] {
    WhiteImages w;
    PileParams params;
    params.objects = 8;
    params.seed = 4;
    params.rig.camera = params.rig.camera.scaled(0.5);
    io::PatternSetSpec patterns;
    patterns.projector_width = params.rig.projector.width;
    patterns.projector_height = params.rig.projector.height;
    patterns.row_codes = false;
    patterns.phase_steps = 0;
    const io::TriangleMesh part = makePart("clamp").mesh;
    w.scene = generatePile(part, params);
    // Every pattern sequence starts with the white image.
    w.clean = renderPileImages(part, w.scene, params, patterns, photometryPreset("clean")).front();
    w.harsh = renderPileImages(part, w.scene, params, patterns, photometryPreset("harsh")).front();
    return w;
  }();
  return images;
}

TEST(PhotometryPreset, HarshPartsAreDarkButTheirHighlightsClip) {
  const WhiteImages& w = whiteImages();
  std::vector<int> clean, harsh;
  int clipped = 0;
  for (std::size_t i = 0; i < w.scene.instance.size(); ++i) {
    if (w.scene.instance[i] < 0 || !w.scene.cloud.points[i].allFinite()) continue;  // lit part pixels
    clean.push_back(w.clean.data[i]);
    harsh.push_back(w.harsh.data[i]);
    clipped += w.harsh.data[i] == 255 ? 1 : 0;
  }
  ASSERT_GT(clean.size(), 1000u);
  const auto median = [](std::vector<int> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  EXPECT_LT(median(harsh), median(clean) / 2);
  const double clipped_share = static_cast<double>(clipped) / static_cast<double>(harsh.size());
  EXPECT_GT(clipped_share, 0.005);
  EXPECT_LT(clipped_share, 0.2);
}

}  // namespace
}  // namespace binpick::simulation
