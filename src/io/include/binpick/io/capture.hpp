#pragma once
// A capture directory: the camera images of one structured-light sequence, in the order they were
// taken, with what is needed to interpret them. The same format is written by the virtual cell and
// by acquisition (record) and read by reconstruction (replay). Layout (docs/capture-format.md):
//   DIR/capture.json        CaptureMetadata
//   DIR/calib.yaml          the rig (rig_calibration.hpp), optional for calibration sequences
//   DIR/images/NNN_<pattern>.png   one image per pattern, 8- or 16-bit grey
// Functions are stateless: thread-safe for different directories. They use OpenMP threads.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace binpick::io {

// What the projector shows, as plain data; reconstruction turns it into patterns and decodes them.
struct PatternSetSpec {
  int projector_width = 1280;  // pixels
  int projector_height = 800;  // pixels
  bool column_codes = true;    // Gray code of the projector column, each bit with its inverse
  bool row_codes = true;       // Gray code of the projector row, each bit with its inverse
  int phase_steps = 4;         // phase-shift images per coded axis (0: none, else >= 3)
  int phase_period = 16;       // projector pixels per sine period (>= 4, a multiple of code_step)
  // Step k shows 1/2 + 1/2 cos(2 pi c / period - theta_k) at projector coordinate c, with
  // theta_k = phase_direction 2 pi k / phase_steps + phase_offset_deg: binpick's own steps advance
  // by +2 pi / N from 0; another rig's may run the other way (-1) or start elsewhere.
  int phase_direction = 1;        // +1 or -1
  double phase_offset_deg = 0.0;  // [0, 360)
  // Projector pixels per code: a rig whose patterns were made at a fraction of the projector's
  // resolution (OpenCV's GrayCodePattern on a 1920x1080 projector at 960x540: 2) codes blocks
  // of code_step x code_step pixels. Coordinates are decoded in codes and reported in pixels.
  int code_step = 1;
  // Projector pixels per Gray-code word, a multiple of code_step (0: code_step, every code its
  // own word). With phase images the Gray code need only say which period a pixel lies in: a
  // complementary Gray code (Zhang et al., Optics and Lasers in Engineering 2012) counts half
  // periods (gray_unit = phase_period / 2, one bit more than the periods need), and the phase
  // gives the position inside the word. At most phase_period; needs phase images when larger
  // than code_step.
  int gray_unit = 0;
  void validate() const;  // throws core::Error naming the field
  // Codes along the projector's width and height: ceil(projector size / code_step).
  int columnCodes() const { return (projector_width + code_step - 1) / code_step; }
  int rowCodes() const { return (projector_height + code_step - 1) / code_step; }
  // Codes per Gray-code word (gray_unit in codes).
  int grayUnitCodes() const { return gray_unit > 0 ? gray_unit / code_step : 1; }
};

struct CaptureMetadata {
  int format_version = 1;
  std::string source;     // e.g. "virtual cell" or the camera's vendor, model and serial
  std::string timestamp;  // ISO 8601, UTC
  int image_width = 0;    // pixels; each side in [1, 65536], at most 2^28 pixels in all
  int image_height = 0;
  int bit_depth = 8;  // 8 or 16 (16-bit images hold the sensor's value in the high bits)
  double exposure_us = 0.0;
  double gain_db = 0.0;
  PatternSetSpec pattern_set;
  std::vector<std::string> patterns;  // pattern names in capture order
  std::vector<std::string> images;    // image file per pattern, relative to the directory
  // When each image arrived, milliseconds after `timestamp` (host clock), one per image; empty
  // when not recorded (the virtual cell). Shows retries and stalls in a recording.
  std::vector<double> frame_times_ms;
};

struct Capture {
  CaptureMetadata metadata;
  std::vector<cv::Mat> images;  // CV_8UC1 or CV_16UC1, one per pattern, in capture order
};

// Reads DIR/capture.json. Throws core::Error "PATH: ..." on a missing file, malformed JSON, a
// missing or mistyped key, an unsupported version, or lists of different lengths.
CaptureMetadata readCaptureMetadata(const std::string& directory);
// Reads the metadata and every image, decoding the images on `threads` threads (0: all cores).
// Throws on a missing, unreadable, extra (an image file in DIR/images that the metadata does not
// list) or wrongly sized image, or one of another bit depth; with several bad images, the error
// names the first in capture order.
Capture readCapture(const std::string& directory, int threads = 0);
// Creates DIR (and DIR/images) and writes the images and then the metadata, each through a
// temporary file and a rename: a directory with a capture.json holds a complete capture. Throws,
// writing nothing, on inconsistent metadata or when DIR already holds a capture (recordings are
// never overwritten).
// `capture.metadata.images` is filled in here from the pattern names. Images are encoded on
// `threads` threads (0: all cores).
void writeCapture(const std::string& directory, Capture capture, int threads = 0);

// The current time as ISO 8601 UTC, e.g. "2026-01-31T12:00:00.123Z".
std::string utcTimestamp();

}  // namespace binpick::io
