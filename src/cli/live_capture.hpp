#pragma once
// The live path on the command line, shared by `capture` and `calibrate rig`: --fake-camera DIR,
// the camera options (camera_options.hpp) and the "Live capture options"
//   [--trigger none|gpio:CHIP:LINE] [--pulse-us P] [--settle-us S] [--timeout-ms T]
//   [--retries R] [--projector WIDTHxHEIGHT] [--phase-steps N]
// A real camera (Aravis) takes one frame per pattern while the projector shows it. A fake camera
// serves a recorded capture's images from an in-process GigE Vision camera on 127.0.0.1 behind
// a virtual projector: the same path without hardware, for tests and demos.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "arguments.hpp"
#include "binpick/io/capture.hpp"

namespace binpick::cli {

// Declares the options above on `command` (`fake_help` says what --fake-camera serves there):
// --camera and --fake-camera exclude each other, and the options only a real camera uses (pixel
// format, trigger, pattern set) need --camera. Returns every option declared, for the command to
// refuse with its other sources of images.
std::vector<CLI::Option*> addLiveCaptureOptions(CLI::App& command, const std::string& fake_help);

// The pattern set of --projector and --phase-steps (rows unless the command declared and got
// --no-rows), validated.
io::PatternSetSpec patternSetFromArguments(const Arguments& args);

// One capture of `patterns` from the camera --camera names, through the projector --trigger
// drives. Throws core::Error naming the option, the camera or the pattern that failed.
io::Capture captureFromCamera(const Arguments& args, const io::PatternSetSpec& patterns);

// One capture through the live path from a fake camera serving `recorded`'s images (its pattern
// set, size and bit depth); the camera options other than the id and pixel format apply.
io::Capture captureFromFake(const Arguments& args, const io::Capture& recorded);

}  // namespace binpick::cli
