#pragma once
// `binpick calibrate hand-eye`: the robot poses from a file (--views DIR,
// calibrate_hand_eye_command.cpp), or sent by the robot in a guided session (--listen,
// calibrate_guided_command.cpp) that records the views and then calibrates from them the same way.
#include <CLI/CLI.hpp>
#include <string>

#include "arguments.hpp"

namespace binpick::cli {

// Declares the guided session's options on `hand_eye`, each refused without `listen`.
void addGuidedSessionOptions(CLI::App& hand_eye, CLI::Option* listen);

// The guided session until its views are in, then the calibration from them.
int runGuidedSession(const Arguments& args);

// The calibration from the views directory `views` (poses.txt and the images) with the
// command's calibration options; prints the views and the result and writes --out.
int calibrateFromViews(const Arguments& args, const std::string& views);

}  // namespace binpick::cli
