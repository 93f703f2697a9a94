#pragma once
// The subcommands of `binpick`. Each returns the process exit code; bad input throws
// core::Error, which main turns into one line on stderr and exit code 1.
#include <string>
#include <vector>

namespace binpick::cli {

int runDetect(const std::vector<std::string>& args);
int runSimulate(const std::vector<std::string>& args);
int runEvaluate(const std::vector<std::string>& args);
int runReconstruct(const std::vector<std::string>& args);
int runCapture(const std::vector<std::string>& args);
int runRobotClient(const std::vector<std::string>& args);
int runGrasps(const std::vector<std::string>& args);     // grasps generated from a part model
int runCalibrate(const std::vector<std::string>& args);  // rig | hand-eye
int runCalibrateRig(const std::vector<std::string>& args);
int runCalibrateHandEye(const std::vector<std::string>& args);        // robot poses from a file
int runCalibrateHandEyeGuided(const std::vector<std::string>& args);  // over the robot protocol

}  // namespace binpick::cli
