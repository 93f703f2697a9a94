// binpick: command-line entry to the bin-picking pipeline.
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "commands.hpp"

namespace {

constexpr const char* kUsage =
    "usage: binpick <command> [options]\n"
    "  detect   --model MODEL --scene SCENE [--max-objects N] [--config FILE] [--out result.json]\n"
    "           [--model-cache FILE] [--threads N] [--method li_hashimoto|drost]\n"
    "  simulate --part NAME [--objects N] [--seed S] --out DIR | --list-parts | --export-part NAME FILE\n"
    "  evaluate --result result.json --truth truth.json --part NAME [--min-visible 0.5]\n";

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    std::cerr << kUsage;
    return argc < 2 ? 2 : 0;
  }
  const std::string command = argv[1];
  const std::vector<std::string> args(argv + 2, argv + argc);
  try {
    if (command == "detect") return binpick::cli::runDetect(args);
    if (command == "simulate") return binpick::cli::runSimulate(args);
    if (command == "evaluate") return binpick::cli::runEvaluate(args);
    std::cerr << "binpick: unknown command '" << command << "'\n" << kUsage;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "binpick " << command << ": " << e.what() << "\n";
    return 1;
  }
}
