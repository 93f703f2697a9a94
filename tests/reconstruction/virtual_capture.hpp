#pragma once
// Test support: captures of a pile in the virtual cell, rendered once per set of options and
// shared by the tests of one executable, with the truth each pixel is checked against.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include "binpick/io/capture.hpp"
#include "binpick/simulation/pile.hpp"

namespace binpick::reconstruction::testing {

struct CaptureOptions {
  std::string part = "clamp";
  int objects = 12;
  uint64_t seed = 7;
  double camera_scale = 1.0;  // the virtual rig's 1280 x 1024 camera binned by this factor
  double bin_length = 0.40;   // metres (PileParams)
  double bin_width = 0.30;
  bool row_codes = true;
  int phase_steps = 4;
  int bit_depth = 8;
  std::string lighting = "clean";  // simulation::photometryPreset
  // Overrides of the preset's PhotometryParams; NaN keeps the preset's.
  double global_light = std::numeric_limits<double>::quiet_NaN();
  double ambient = std::numeric_limits<double>::quiet_NaN();
  double projector_blur = std::numeric_limits<double>::quiet_NaN();  // min_blur_sigma
  int mixed_pixel_samples = 1;  // PhotometryParams::mixed_pixel_samples: 1, one ray per pixel
  int code_step = 1;            // PatternSetSpec::code_step (the phase period scales with it)
  int phase_period = 16;        // PatternSetSpec::phase_period, in codes
  int gray_unit = 0;            // PatternSetSpec::gray_unit, in codes (0: one code per word)
  bool operator<(const CaptureOptions& other) const;
};

struct VirtualCapture {
  simulation::PileParams params;
  simulation::PileScene scene;
  io::Capture capture;

  // Where the surface point seen by `pixel` lands in the projector image (NaN: nothing seen).
  Eigen::Vector2d trueProjectorPixel(std::size_t pixel) const;
  // The pixel sees a surface that the projector lights (an ideal sensor measures it).
  bool measurable(std::size_t pixel) const;
  // The pixel sees a surface that the projector does not light.
  bool inShadow(std::size_t pixel) const;
  std::size_t pixelCount() const { return scene.depth.size(); }
};

const VirtualCapture& virtualCapture(const CaptureOptions& options);

// A copy whose images own their pixels: cv::Mat copies share them, and the cached captures must
// stay untouched by tests that damage theirs.
io::Capture deepCopy(const io::Capture& capture);

}  // namespace binpick::reconstruction::testing
