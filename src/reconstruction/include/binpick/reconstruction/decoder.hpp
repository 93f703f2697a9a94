#pragma once
// Decoding a structured-light capture: for every camera pixel, the projector column (and row)
// whose light it sees, to sub-pixel precision when the capture has phase-shift images.
//
// Per pixel (a tile of consecutive pixels at a time, vectorised by the compiler):
// 1. Light: contrast = white - black; with direct and global light separated after Moreno &
//    Taubin (3DIMPVT 2012) from the high-frequency Gray-code images:
//      L_d = (L_max - L_min) / (1 - b),   L_g = 2 (L_min - b L_max) / (1 - b^2).
//    Too little direct light: Unlit (projector shadow, nothing there, too dark).
// 2. Bits: each Gray bit is compared with its inverse and classified 1, 0 or uncertain by the
//    rules of Xu & Aliaga as used by Moreno & Taubin, so that interreflections do not flip bits;
//    near-ties (stripe edges) are uncertain too.
// 3. Code: the columns consistent with the certain bits must form a short run (a pixel on a
//    stripe edge sees two adjacent columns); otherwise UncertainCode. Without phase, the pixel's
//    position is the run's centre.
// 4. Phase: phi = atan2(sum I_k sin(2 pi k/N), sum I_k cos(2 pi k/N)), unwrapped temporally by
//    the Gray-code run: the period instance that falls within the run (PhaseMismatch if none).
// 5. Gray code only: the dark pixels that failed are read again with the dark pixels of their
//    stripe, their differences summed along it (stripe_reading.hpp; DecodedCapture::stripe_run).
// Stateless: thread-safe.
#include <cstddef>
#include <opencv2/core.hpp>

#include "binpick/io/capture.hpp"
#include "binpick/reconstruction/pixel_status.hpp"

namespace binpick::reconstruction {

// Intensities are in 8-bit counts (0..255); for 16-bit captures every threshold is scaled by 257.
struct DecodeParams {
  // A pixel needs at least this much white-minus-black contrast, and this much direct light L_d,
  // to be decoded. Counts.
  double min_contrast = 6.0;
  double min_direct = 4.0;
  // The share of white a black projector pixel still emits (Moreno & Taubin's b).
  double projector_black_level = 0.0;
  // Direct and global light are estimated from the Gray bits whose stripes are between these
  // widths (projector pixels): fine enough that interreflections see half of them lit, coarse
  // enough that projector defocus does not wash them out.
  int separation_min_stripe = 4;
  int separation_max_stripe = 16;
  // A bit whose pattern and inverse differ by less than max(min_bit_difference,
  // bit_margin * L_d, bit_noise_sigmas * sigma) counts is uncertain. sigma is the standard
  // deviation of pattern - inverse at the pixel's brightness, from the sensor's read + shot noise
  // measured on the capture itself (pattern + inverse - white - black is pure noise); 0 turns
  // that term off.
  double min_bit_difference = 2.0;
  double bit_margin = 0.15;
  double bit_noise_sigmas = 3.0;
  // Longest run of projector columns (rows) the uncertain bits may leave open. Gray-code only:
  // a pixel on a stripe edge sees 2 columns; with phase, the phase decides within the run, which
  // must stay well inside one phase period.
  int max_code_run_without_phase = 2;
  int max_code_run_with_phase = 4;
  // Phase-shift images: the sinusoid's amplitude must be at least this many counts, and the
  // unwrapped position may lie at most this far (projector pixels) outside the Gray-code run.
  double min_phase_amplitude = 3.0;
  double max_phase_gray_disagreement = 1.0;
  // A pixel whose column decoded but whose row did not keeps its column (row NaN): triangulation
  // intersects the camera ray with the column's light alone. With a horizontal baseline the row
  // carries almost no depth, so little is lost; false: such pixels take the row's status. The
  // Reconstructor decodes with false on a rig whose baseline lies less than half across the
  // projector's columns (a projector above the camera: the column alone carries little depth).
  bool keep_column_without_row = true;
  // A pixel whose column Gray code leaves too long a run (noise on a dark surface undecides
  // coarse bits far from their stripe edges) but whose phase is usable takes the period named by
  // its neighbours when at least this many of its 8 neighbours decoded within a quarter of a
  // period of each other, the instance chosen lies within 0.5 + max_phase_gray_disagreement of
  // their median, and the certain bits agree with it (neighbour_unwrap.hpp). Fewer than 5 let
  // pixels beside depth edges through. 0: off (such pixels stay UncertainCode).
  int min_unwrap_neighbours = 5;
  // Gray-code-only captures: a dark pixel left Unlit or UncertainCode (its contrast 1 to 4 noise
  // margins) is read again with the dark pixels of its stripe that also failed, within this many
  // pixels each side (stripe_reading.hpp): black surfaces, where the finest bits drown in the
  // noise. Each bit must clear bit_noise_sigmas of the summed noise (so this needs the noise
  // measured). 0: off.
  int stripe_reach = 8;
  // Such a pixel is placed in the shortest run of codes that holds 95% of the likelihood its
  // uncertain bits leave, when that run is at most this long (the finest bits dropped where
  // darkness erased them): a coarser point than the others', about half the run from the truth.
  int max_code_run_along_stripe = 8;
  // Capture-level checks (throw): the share of pixels the white image may saturate, and how far
  // a Gray pair's sum may drift from white + black (a missing or shuffled frame) before the
  // capture is refused.
  double max_saturated_fraction = 0.5;
  double max_pair_sum_error = 0.25;
  int threads = 0;        // 0: all cores
  void validate() const;  // throws core::Error naming the field
};

// Copies share the cv::Mat pixels (as cv::Mat does): clone() a member before changing it.
struct DecodedCapture {
  int width = 0;  // camera image size
  int height = 0;
  // Projector pixel coordinates seen by each camera pixel (pixel centres at integers, as in
  // LensIntrinsics), CV_32FC1; NaN where status is not Valid. `row` is empty when the capture
  // has no row codes, and NaN at Valid pixels whose row did not decode (keep_column_without_row).
  cv::Mat column;
  cv::Mat row;
  // CV_8UC1 PixelStatus per pixel.
  cv::Mat status;
  // CV_32FC1: the standard deviation of `column` the sensor's noise gives it (projector pixels),
  // from the noise measured on the capture and the pixel's phase amplitude:
  // sqrt(2 / N) sigma_I / B * period / (2 pi) for N steps of amplitude B, sigma_I^2 the
  // variance of one image at the steps' mean. NaN where status is not Valid. Empty when the
  // capture has no phase-shift images or its noise could not be measured. Where the sensor
  // clipped phase steps it is that of the clipped sinusoid (an approximation).
  cv::Mat column_noise;
  // CV_8UC1, Gray-code-only captures: for the pixels read along their stripes
  // (DecodeParams::stripe_reach), how many codes their readable bits left open (the point lies
  // within half of that of the truth); 0 for the pixels read alone. Empty when none was.
  cv::Mat stripe_run;
  // CV_32FC1: the white image scaled to [0, 1] (the sensor's full scale), for display.
  cv::Mat intensity;
  bool has_phase = false;  // the capture had phase-shift images (sub-pixel coordinates)
  int code_step = 1;       // projector pixels per code (io::PatternSetSpec::code_step)
};

// Throws core::Error naming what is wrong when the capture cannot be decoded as a whole: the
// images do not match the metadata's pattern set (count, order, size, type), the white image is
// no brighter than the black one (projector off), the white image is saturated over more than
// max_saturated_fraction of the lit pixels, a Gray pair does not add up to white + black (a
// missing, black or shuffled frame), or the phase disagrees with the Gray code on most well-lit
// pixels in a way that swapping a Gray pattern with its inverse, or two phase steps, undoes (the
// message names the two images).
DecodedCapture decodeCapture(const io::Capture& capture, const DecodeParams& params = {});

}  // namespace binpick::reconstruction
