// binpickd: the bin-picking cell service. It serves robot controllers over TCP: capture (camera +
// projector, or replay of recorded captures), reconstruct, detect, plan picks, send them.
//   binpickd --config FILE [--port N] [--port-file FILE] [--check]
// --check loads and prepares everything (writing the model caches), then exits: 0 when the
// settings are good.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "binpick/cell/cell_config.hpp"
#include "binpick/cell/cell_setup.hpp"
#include "daemon.hpp"

namespace {

constexpr const char* kUsage = "usage: binpickd --config FILE [--port N] [--port-file FILE] [--check] [--verbose]\n";

struct CommandLine {
  binpick::daemon::DaemonOptions options;
  bool check = false;
  bool verbose = false;
};

CommandLine parse(const std::vector<std::string>& args) {
  CommandLine line;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    const bool has_value = i + 1 < args.size();
    if (arg == "--check")
      line.check = true;
    else if (arg == "--verbose")
      line.verbose = true;
    else if (arg == "--config" && has_value)
      line.options.config_path = args[++i];
    else if (arg == "--port-file" && has_value)
      line.options.port_file = args[++i];
    else if (arg == "--port" && has_value)
      line.options.port_override = std::stoi(args[++i]);
    else
      throw binpick::core::Error("unknown or incomplete option '" + arg + "'");
  }
  if (line.options.config_path.empty()) throw binpick::core::Error("--config FILE is needed");
  return line;
}

int check(const std::string& path) {
  const auto setup = binpick::cell::prepareCell(binpick::cell::loadCellConfig(path));
  std::cout << path << ": " << setup->recipes.size() << " recipe(s) ready in " << static_cast<int>(setup->prepare_ms)
            << " ms" << (setup->reconstructor ? "" : "; calibration: " + setup->calibration_problem) << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  binpick::daemon::blockStopAndReloadSignals();  // before any thread starts
  try {
    const CommandLine line = parse(std::vector<std::string>(argv + 1, argv + argc));
    // One stream for the journal (stderr, like every component's logger); journald adds the time.
    spdlog::set_default_logger(spdlog::stderr_color_mt("binpickd"));
    spdlog::set_pattern("[%l] %n: %v");
    if (line.verbose) spdlog::set_level(spdlog::level::debug);
    if (line.check) return check(line.options.config_path);
    return binpick::daemon::runDaemon(line.options);
  } catch (const std::invalid_argument&) {
    std::cerr << "binpickd: --port needs a number\n" << kUsage;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "binpickd: " << e.what() << "\n";
    return 1;
  }
}
