#pragma once
// Image formation of the virtual structured-light camera: from what each camera pixel sees (its
// PixelLighting, pattern-independent) to the 8- or 16-bit image under every pattern of a set.
//   signal = ambient + direct * P(x, y) + global * mean(P)
// where P is the projector's emitted brightness (black level included) blurred by the projector's
// defocus at the pixel, then shot + read noise and the sensor's saturation and quantisation. A
// mixed pixel (MixedPixels: one that straddles a depth edge) gathers the light of every surface
// it sees, each by its share, before the noise.
// Stateless functions: thread-safe.
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "binpick/io/capture.hpp"

namespace binpick::simulation {

struct PhotometryParams {
  // Counts a full-white projector pixel gives on a white Lambertian surface facing the projector
  // at `reference_distance` (8-bit full scale is 255).
  double projector_white = 280.0;
  double reference_distance = 0.9;      // metres
  double projector_black_level = 0.01;  // share of white a black projector pixel still emits
  double ambient = 6.0;                 // counts on a white surface from room light
  // Multiplies the diffuse reflectance of every surface (parts and bin): dark, e.g. oiled or
  // blackened, parts. Highlights (specular) are not scaled.
  double albedo_scale = 1.0;
  // Indirect light (interreflections in the bin): share of the direct white light that reaches a
  // surface from elsewhere; it follows the pattern's mean brightness, not its local value.
  double global_light = 0.03;
  double specular = 0.15;       // Blinn-Phong weight relative to the diffuse albedo 1
  double shininess = 40.0;      // Blinn-Phong exponent
  double focus_distance = 0.9;  // metres from the projector where patterns are sharp
  // Defocus blur (Gaussian sigma, projector pixels) per dioptre away from focus: sigma =
  // hypot(min_blur_sigma, defocus_per_dioptre * |1/d - 1/focus_distance|).
  double defocus_per_dioptre = 6.0;
  double min_blur_sigma = 0.4;    // projector pixels: optics and the camera pixel's footprint
  double read_noise = 0.7;        // counts (standard deviation)
  double shot_noise_gain = 0.03;  // counts per electron: shot variance = gain * signal
  int bit_depth = 8;              // 8 or 16 (16 scales the 8-bit counts by 257)
  // Mixed pixels: a camera pixel gathers light from its whole area, widened by the lens's blur,
  // so one beside a depth edge (a part's rim over the floor several centimetres behind) sees both
  // surfaces and decodes to the one that gives it more light, or to a position between them, as
  // on a real sensor. Where a pixel's ray and a neighbour's see different objects, nothing and
  // something, or depths more than 8 pixel footprints apart, the pile renderer (pile.hpp) traces
  // mixed_pixel_samples x mixed_pixel_samples rays spread over what the pixel gathers (at that
  // pixel and at those within the blur's reach) and sums the light of each surface they see by
  // its share. Away from depth edges the lens's blur only adds to the projector's
  // (min_blur_sigma) and is not traced. 1 (the default): one ray through each pixel centre, no
  // mixed pixels; 3 adds about 0.2 to 0.35 s to a 1280 x 1024 pile capture (of 2 to 5 s), and
  // the one-ray truth the decoder's tests compare with no longer holds at edge pixels. The
  // calibration-board renderer always traces one ray.
  int mixed_pixel_samples = 1;
  double camera_blur_sigma = 0.5;  // camera pixels: the lens's point spread (Gaussian), traced at edges
  uint64_t seed = 1;
  int threads = 0;        // 0: all cores
  void validate() const;  // throws core::Error naming the field
};

// What one camera pixel sees, in 8-bit counts, independent of the pattern.
struct PixelLighting {
  float projector_x = 0.0f;  // projector pixel coordinates of the surface point (centre = integer)
  float projector_y = 0.0f;
  float blur_sigma = 0.0f;  // projector pixels
  float direct = 0.0f;      // counts from a full-white projector (0 when the point is not lit)
  float ambient = 0.0f;     // counts that no pattern changes
  float global = 0.0f;      // counts of indirect light under a full-white projection
};

// What a pixel that straddles a depth edge sees (a mixed pixel): several surfaces, each filling a
// share of what the pixel gathers. The shares sum to at most 1 (the rest sees nothing).
struct SeenSurface {
  PixelLighting light;
  float share = 0.0f;
};

struct MixedPixels {
  std::vector<std::size_t> pixel;  // image index (row-major) of each mixed pixel
  // Pixel m sees surfaces[first[m]] up to, not including, surfaces[first[m + 1]]: `first` has one
  // entry more than `pixel` (or none when there are no mixed pixels).
  std::vector<std::size_t> first;
  std::vector<SeenSurface> surfaces;
};

// One image per pattern of `spec` (patternSequence order), `width` x `height`, CV_8UC1 or
// CV_16UC1. Noise is keyed by (pattern, pixel): the same seed gives the same images on any
// number of threads. A mixed pixel's signal is the share-weighted sum of its surfaces' (their
// entries in `pixels` are not used). Throws core::Error on a size mismatch, mixed pixels outside
// the image or repeated, `first` not a partition of `surfaces`, a share not in [0, 1], or bad
// params.
std::vector<cv::Mat> renderPatternImages(const std::vector<PixelLighting>& pixels, int width, int height,
                                         const io::PatternSetSpec& spec, const PhotometryParams& params,
                                         const MixedPixels& mixed = {});

// renderPatternImages(...).front(), the white image, alone: the same pixels for a fraction of
// the cost, for views that need no patterns (hand-eye sessions).
cv::Mat renderWhiteImage(const std::vector<PixelLighting>& pixels, int width, int height,
                         const io::PatternSetSpec& spec, const PhotometryParams& params);

}  // namespace binpick::simulation
