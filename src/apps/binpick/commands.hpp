#pragma once
// The subcommands of `binpick`. Each returns the process exit code; bad input throws
// binpick::Error, which main turns into one line on stderr and exit code 1.
#include <string>
#include <vector>

namespace binpick::cli {

int runDetect(const std::vector<std::string>& args);
int runSimulate(const std::vector<std::string>& args);
int runEvaluate(const std::vector<std::string>& args);
int runReconstruct(const std::vector<std::string>& args);
int runCapture(const std::vector<std::string>& args);
int runRobotClient(const std::vector<std::string>& args);

}  // namespace binpick::cli
