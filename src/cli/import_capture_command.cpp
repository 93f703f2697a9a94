// binpick import-capture --images DIR [--glob PATTERN] (--sequence FILE.yaml | --preset NAME
//     [--projector WxH] [--code-step N]) (--calib calib.yaml | --opencv-calib FILE [--units mm|m])
//     --out CAPTURE_DIR
// A capture from another rig, as its images come (PNG, BMP or TIFF, 8 or 16 bit, any names),
// written as a capture directory that reconstruct, detect and binpickd's replay read: the images
// in the order the rig's sequence lists them, named by pattern, and the calibration as calib.yaml.
#include <filesystem>
#include <iostream>

#include "arguments.hpp"
#include "binpick/core/error.hpp"
#include "binpick/core/yaml_section.hpp"
#include "binpick/io/capture.hpp"
#include "binpick/io/capture_import.hpp"
#include "binpick/io/opencv_calibration.hpp"
#include "binpick/io/rig_calibration.hpp"
#include "binpick/reconstruction/decoder.hpp"
#include "binpick/reconstruction/pixel_status.hpp"
#include "binpick/reconstruction/rig_sequence.hpp"
#include "commands.hpp"
#include "live_capture.hpp"

namespace binpick::cli {
namespace {

namespace fs = std::filesystem;

reconstruction::RigSequence sequenceFrom(const Arguments& args) {
  if (const auto file = args.value("--sequence")) return reconstruction::readRigSequence(*file);
  const auto preset = args.value("--preset");
  if (!preset) throw missingOption("--sequence or --preset");
  io::PatternSetSpec spec = patternSetFromArguments(args);
  spec.code_step = args.integer("--code-step").value_or(1);
  core::validateSettings("--code-step", [&] { spec.validate(); });
  return reconstruction::presetSequence(*preset, spec);
}

std::string sequenceText(const reconstruction::RigSequence& sequence) {
  const io::PatternSetSpec& s = sequence.spec;
  return std::to_string(sequence.patterns.size()) + " images for a " + std::to_string(s.projector_width) + "x" +
         std::to_string(s.projector_height) + " projector at code step " + std::to_string(s.code_step);
}

io::RigCalibration calibrationFrom(const Arguments& args, const io::PatternSetSpec& spec) {
  if (const auto file = args.value("--calib")) return io::readRigCalibration(*file);
  const auto opencv = args.value("--opencv-calib");
  if (!opencv) throw missingOption("--calib or --opencv-calib");
  io::OpenCvCalibrationOptions options;
  options.units = io::lengthUnitFromName(args.value("--units").value_or("mm"));
  options.projector_width = spec.projector_width;
  options.projector_height = spec.projector_height;
  return io::readOpenCvCalibration(*opencv, options);
}

// The calibration must be of this camera and this projector, or every ray is wrong.
void checkRigFits(const io::RigCalibration& rig, const io::Capture& capture) {
  const io::CaptureMetadata& m = capture.metadata;
  const auto size = [](int w, int h) { return std::to_string(w) + "x" + std::to_string(h); };
  if (rig.camera.width != m.image_width || rig.camera.height != m.image_height) {
    throw core::Error("the calibration's camera is " + size(rig.camera.width, rig.camera.height) + ", the images are " +
                      size(m.image_width, m.image_height));
  }
  if (rig.projector.width != m.pattern_set.projector_width || rig.projector.height != m.pattern_set.projector_height) {
    throw core::Error("the calibration's projector is " + size(rig.projector.width, rig.projector.height) +
                      ", the sequence's " + size(m.pattern_set.projector_width, m.pattern_set.projector_height) +
                      " (--projector)");
  }
}

// Codes beyond the projector mean the patterns were made for another size or code step than the
// one given: rows past the projector's bottom would be dropped silently (and a column alone
// triangulates poorly when the baseline runs along the columns). Decoded once, with rows kept
// only where they fit, so that every out-of-range code shows.
constexpr double kMaxOutOfRangeShare = 0.05;  // of the pixels whose codes were read

void requireCodesInsideProjector(const io::Capture& capture) {
  reconstruction::DecodeParams params;
  params.keep_column_without_row = false;
  const reconstruction::StatusCounts counts =
      reconstruction::countStatuses(reconstruction::decodeCapture(capture, params).status);
  const auto at = [&](reconstruction::PixelStatus s) { return counts[static_cast<std::size_t>(s)]; };
  const std::size_t outside = at(reconstruction::PixelStatus::CodeOutOfRange);
  const std::size_t read =
      outside + at(reconstruction::PixelStatus::Valid) + at(reconstruction::PixelStatus::PhaseMismatch);
  if (read == 0 || static_cast<double>(outside) <= kMaxOutOfRangeShare * static_cast<double>(read)) return;
  const io::PatternSetSpec& spec = capture.metadata.pattern_set;
  throw core::Error(std::to_string(100 * outside / read) +
                    "% of the pixels whose codes were read name codes beyond a " +
                    std::to_string(spec.projector_width) + "x" + std::to_string(spec.projector_height) +
                    " projector at code step " + std::to_string(spec.code_step) + " (" +
                    std::to_string(spec.columnCodes()) + "x" + std::to_string(spec.rowCodes()) +
                    " codes): give the projector size and code step the patterns were made for (--projector, "
                    "--code-step, or the sequence file's)");
}

int run(const Arguments& args) {
  const std::string images = args.required("--images");
  const std::string out = args.required("--out");
  const reconstruction::RigSequence sequence = sequenceFrom(args);
  const std::vector<std::string> files = io::listImageFiles(images, args.value("--glob").value_or(""));
  const auto name = [](const std::string& file) { return fs::path(file).filename().string(); };
  if (files.size() != sequence.patterns.size()) {
    throw core::Error("--images " + images + ": " + std::to_string(files.size()) + " images" +
                      (files.empty() ? "" : " (" + name(files.front()) + " .. " + name(files.back()) + ")") +
                      ", but the sequence has " + sequenceText(sequence));
  }
  const io::RigCalibration rig = calibrationFrom(args, sequence.spec);
  int shifted_bits = 0;
  io::Capture capture =
      io::importImages(files, sequence.spec, sequence.patterns, "imported from " + images, &shifted_bits);
  if (shifted_bits > 0) std::cout << "16-bit images held " << 16 - shifted_bits << "-bit values: shifted up\n";
  checkRigFits(rig, capture);
  requireCodesInsideProjector(capture);
  io::writeCapture(out, std::move(capture));
  io::writeRigCalibration((fs::path(out) / "calib.yaml").string(), rig);
  std::cout << "imported " << files.size() << " images (" << name(files.front()) << " as " << sequence.patterns.front()
            << " .. " << name(files.back()) << " as " << sequence.patterns.back() << ") into " << out << "\n";
  return 0;
}

}  // namespace

void addImportCaptureCommand(CLI::App& program, CommandTable& table) {
  CLI::App& command =
      table.add(program, "import-capture", "Turn another rig's pattern images into a capture directory", run);
  addText(command, "--images", "DIR", "The rig's images: PNG, BMP or TIFF, 8 or 16 bit, in natural name order")
      ->required();
  addText(command, "--glob", "PATTERN", "Only the files matching this (e.g. 'graycode_*.png')");
  CLI::Option* sequence = addText(command, "--sequence", "FILE", "What the rig projects, image by image (YAML)");
  CLI::Option* preset =
      addText(command, "--preset", "NAME", "A known sequence instead: binpick or opencv-graycode")->excludes(sequence);
  addText(command, "--projector", "WxH", "The projector's size in pixels (with --preset; default 1280x800)")
      ->needs(preset);
  addInteger(command, "--code-step", "N", "Projector pixels per code (with --preset; default 1)")->needs(preset);
  addInteger(command, "--phase-steps", "N", "Phase-shift images per axis (--preset binpick; default 4)")->needs(preset);
  addFlag(command, "--no-rows", "No row codes (--preset binpick)")->needs(preset);
  CLI::Option* calib = addText(command, "--calib", "FILE", "The rig calibration (calib.yaml)");
  CLI::Option* opencv = addText(command, "--opencv-calib", "FILE",
                                "Or another tool's OpenCV FileStorage calibration (XML/YAML: stereoCalibrate's)")
                            ->excludes(calib);
  addText(command, "--units", "mm|m", "The unit of --opencv-calib's translation (default mm)")->needs(opencv);
  addText(command, "--out", "DIR", "Write the capture directory here (must not hold a capture)")->required();
}

}  // namespace binpick::cli
