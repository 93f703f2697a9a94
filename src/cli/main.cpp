// binpick: command-line entry to the bin-picking pipeline.
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "commands.hpp"

namespace {

constexpr const char* kUsage =
    "usage: binpick <command> [options]\n"
    "  capture  (--camera ID | --fake-camera CAPTURE_DIR) --out DIR [--pixel-format Mono8]\n"
    "           [--exposure-us E] [--gain-db G] [--trigger none|gpio:CHIP:LINE] [--pulse-us P]\n"
    "           [--settle-us S] [--timeout-ms T] [--retries R] [--projector WxH] [--phase-steps N]\n"
    "           [--no-rows] [--calib FILE]\n"
    "  reconstruct --capture DIR [--calib FILE] [--config FILE] [--threads N] [--out cloud.ply]\n"
    "              [--status status.png]\n"
    "  detect   --model MODEL (--scene CLOUD | --capture DIR [--calib FILE]) [--max-objects N]\n"
    "           [--config FILE] [--out result.json] [--model-cache FILE] [--threads N]\n"
    "           [--method li_hashimoto|drost]\n"
    "  simulate (--part NAME | --mesh FILE) [--objects N] [--seed S] [--cloud-only] --out DIR\n"
    "           | (--part NAME | --mesh FILE) [--objects N] [--seed S] --empty-bin\n"
    "             [--gripper suction|parallel] [--max-cycles K] --out DIR\n"
    "           | --calibration-board charuco|chessboard --poses K --out DIR\n"
    "           | --hand-eye eye-to-hand|eye-in-hand [--views K] [--seed S] [--robot-noise-mm M]\n"
    "             [--robot-noise-deg D] [--orientation NAME] --out DIR\n"
    "           | --list-parts | --export-part NAME FILE\n"
    "  evaluate --result result.json --truth CAPTURE_DIR [--part NAME] [--min-visible 0.5]\n"
    "  calibrate rig (--sequence DIR | --views DIR... | (--camera ID | --fake-camera SEQUENCE_DIR)\n"
    "           --record DIR [--count K] [capture's camera options]) [--board charuco|chessboard]\n"
    "           [--squares 9x7] [--square-mm 30] [--marker-mm 22] [--dictionary DICT_5X5_100]\n"
    "           [--min-views 8] [--drop-outliers] [--outlier-factor 3] [--outlier-floor-px 0.5]\n"
    "           [--corner-window 40] --out calib.yaml\n"
    "  calibrate hand-eye --views DIR --calib calib.yaml --setup eye-to-hand|eye-in-hand\n"
    "           [--board charuco|chessboard] [--squares 9x7] [--square-mm 30] [--marker-mm 22]\n"
    "           [--dictionary DICT_5X5_100] [--method shah|li|tsai|park|horaud|andreff|daniilidis]\n"
    "           [--min-views N] [--refine] --out hand_eye.yaml\n"
    "  calibrate hand-eye --listen --record DIR --count K (--camera ID [--pixel-format F]\n"
    "           [--exposure-us E] [--gain-db G] [--timeout-ms T] | --replay IMAGES_DIR) [--port N]\n"
    "           [--port-file F] [--framing ascii|binary] [--orientation NAME] [--byte-order big|little]\n"
    "           --calib calib.yaml --setup eye-to-hand|eye-in-hand [board options] [--method NAME]\n"
    "           [--min-views N] [--refine] --out hand_eye.yaml\n"
    "  grasps   (--model MODEL [--model-scale S] | --part NAME) --gripper suction|parallel\n"
    "           [--cup-diameter M] [--seal-tolerance M] [--tool-radius M] [--tool-length M] [--stroke M]\n"
    "           [--finger-width M] [--finger-depth M] [--symmetry-order N --symmetry-axis x,y,z]\n"
    "           [--continuous-axis x,y,z] [--seed S] [--max-grasps N] [--spacing M] --out grasps.yaml\n"
    "           [--image grasps.png]\n"
    "  robot-client [--host H] [--port P] [--framing ascii|binary] [--orientation NAME]\n"
    "               [--byte-order big|little] [--timeout-ms T] [--connect-timeout-ms T] [--cycles N]\n"
    "               [--model NAME] [--send \"CMD[,ARG];...\"]\n";

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
    if (command == "reconstruct") return binpick::cli::runReconstruct(args);
    if (command == "capture") return binpick::cli::runCapture(args);
    if (command == "robot-client") return binpick::cli::runRobotClient(args);
    if (command == "grasps") return binpick::cli::runGrasps(args);
    if (command == "calibrate") return binpick::cli::runCalibrate(args);
    std::cerr << "binpick: unknown command '" << command << "'\n" << kUsage;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "binpick " << command << ": " << e.what() << "\n";
    return 1;
  }
}
