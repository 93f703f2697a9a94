// binpick simulate (--part NAME | --mesh FILE [--mesh-scale S]) [--objects N] [--seed S]
//                  [--bin-length L --bin-width W --bin-wall-height H] [--camera-height Z]
//                  [--bit-depth 8|16] [--cloud-only] [--threads T] --out DIR
// binpick simulate (--part NAME | --mesh FILE [--mesh-scale S]) [--objects N] [--seed S] --empty-bin
//                  [--gripper suction|parallel] [--cup-diameter M] [--tool-radius M] [--stroke M]
//                  [--max-cycles K] [bin options] --out DIR (emptying.hpp)
// binpick simulate --calibration-board charuco|chessboard [--poses K] [--seed S] --out DIR
// binpick simulate --hand-eye eye-to-hand|eye-in-hand [--views K] ... --out DIR (simulate_hand_eye.hpp)
// binpick simulate --list-parts
// binpick simulate --export-part NAME FILE
// A pile writes one capture directory (docs/capture-format.md): capture.json, calib.yaml,
// images/ and truth/; with --cloud-only, cloud.ply (the ideal structured-light cloud) instead of
// the images.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>

#include "arguments.hpp"
#include "binpick/core/error.hpp"
#include "binpick/core/stopwatch.hpp"
#include "binpick/emptying/emptying.hpp"
#include "binpick/io/geometry_io.hpp"
#include "binpick/simulation/calibration_sequence.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/pile.hpp"
#include "binpick/simulation/pile_truth.hpp"
#include "commands.hpp"
#include "simulate_hand_eye.hpp"

namespace binpick::cli {
namespace {

namespace fs = std::filesystem;

int listParts() {
  for (const std::string& name : simulation::partNames()) {
    std::cout << name << "  " << simulation::makePart(name).description << "\n";
  }
  return 0;
}

// A built-in part, or a user's mesh file (its symmetry unknown: none is assumed).
simulation::Part partFrom(const Arguments& args) {
  if (args.value("--part") && args.value("--mesh")) {
    throw core::Error("simulate: give --part or --mesh, not both");
  }
  if (args.value("--part")) return simulation::makePart(*args.value("--part"));
  simulation::Part part;
  part.name = args.required("--mesh");
  part.mesh = io::readMesh(part.name);
  const double scale = args.number("--mesh-scale").value_or(1.0);
  if (!(scale > 0.0)) throw core::Error("--mesh-scale must be positive");
  for (auto& v : part.mesh.vertices) v *= static_cast<float>(scale);
  return part;
}

// Refuses to mix a new capture into an old one: the output directory must be new or empty.
void requireFreshDirectory(const fs::path& out) {
  if (fs::exists(out) && !(fs::is_directory(out) && fs::is_empty(out))) {
    throw core::Error(out.string() + ": already exists and is not empty; choose a new --out directory");
  }
  fs::create_directories(out);
}

simulation::PileParams pileParams(const Arguments& args) {
  simulation::PileParams params;
  params.objects = args.integer("--objects").value_or(params.objects);
  params.seed = static_cast<uint64_t>(args.integer("--seed").value_or(1));
  params.threads = args.integer("--threads").value_or(0);
  params.bin_length = args.number("--bin-length").value_or(params.bin_length);
  params.bin_width = args.number("--bin-width").value_or(params.bin_width);
  params.bin_wall_height = args.number("--bin-wall-height").value_or(params.bin_wall_height);
  params.camera_height = args.number("--camera-height").value_or(params.camera_height);
  params.validate();
  return params;
}

// The closed pick loop: one line per cycle, emptying.json and the cell's files under --out.
int emptyBin(const Arguments& args) {
  const simulation::Part part = partFrom(args);
  emptying::EmptyingParams params;
  params.pile = pileParams(args);
  params.photometry.seed = params.pile.seed;
  params.photometry.threads = params.pile.threads;
  params.gripper.type = picking::gripperTypeFromName(args.value("--gripper").value_or("suction"));
  params.gripper.cup_diameter = args.number("--cup-diameter").value_or(params.gripper.cup_diameter);
  params.gripper.tool_radius = args.number("--tool-radius").value_or(params.gripper.tool_radius);
  params.gripper.stroke = args.number("--stroke").value_or(params.gripper.stroke);
  params.max_cycles = args.integer("--max-cycles").value_or(0);
  params.out_directory = args.required("--out");
  requireFreshDirectory(params.out_directory);
  const emptying::EmptyingReport report = emptying::emptyBin(
      part, params, [](const emptying::CycleRecord& cycle) { std::cout << emptying::cycleLine(cycle) << std::endl; });
  std::cout << emptying::summaryLine(report) << "\n";
  for (const emptying::PartLeft& left : report.left) {
    const Eigen::Vector3d t = left.T_base_part.translation() * 1000.0;
    std::cout << "  left: part " << left.index << " at (" << std::lround(t.x()) << ", " << std::lround(t.y()) << ", "
              << std::lround(t.z()) << ") mm in the robot base, " << std::lround(100 * left.visible_fraction)
              << "% visible\n";
  }
  return 0;
}

int simulatePile(const Arguments& args) {
  const core::Stopwatch stopwatch;
  const simulation::Part part = partFrom(args);
  const simulation::PileParams params = pileParams(args);
  simulation::PhotometryParams photometry;
  photometry.bit_depth = args.integer("--bit-depth").value_or(8);
  photometry.seed = params.seed;
  photometry.threads = params.threads;
  photometry.validate();
  io::PatternSetSpec patterns;
  patterns.projector_width = params.rig.projector.width;
  patterns.projector_height = params.rig.projector.height;

  const fs::path out = args.required("--out");
  requireFreshDirectory(out);
  simulation::PileScene scene;
  if (args.flag("--cloud-only")) {
    scene = simulation::generatePile(part.mesh, params);
    io::writePointCloud((out / "cloud.ply").string(), scene.cloud);
  } else {
    simulation::PileCapture simulated = simulation::generatePileCapture(part.mesh, params, patterns, photometry);
    scene = std::move(simulated.scene);
    const std::string source = "binpick virtual cell (part " + part.name + ", " + std::to_string(params.objects) +
                               " objects, seed " + std::to_string(params.seed) + ")";
    io::writeCapture(out.string(),
                     simulation::recordedCapture(std::move(simulated.images), params, patterns, photometry, source));
  }
  io::writeRigCalibration((out / "calib.yaml").string(), scene.rig);
  simulation::writePileTruth(out.string(), scene, part.name, part.mesh);
  std::cerr << "simulated " << scene.objects.size() << " x " << part.name << " into " << out.string() << " ("
            << stopwatch.elapsedMs() / 1000 << " s" << (scene.physics.settled ? "" : ", pile not settled") << ")\n";
  if (scene.physics.lost > 0) {
    std::cerr << scene.physics.lost << " of " << params.objects << " parts did not stay in the bin and were left out\n";
  }
  return 0;
}

int simulateCalibration(const Arguments& args) {
  simulation::CalibrationSequenceParams params;
  params.board.type = simulation::boardTypeFromName(args.required("--calibration-board"));
  params.poses.count = args.integer("--poses").value_or(params.poses.count);
  params.poses.seed = static_cast<uint64_t>(args.integer("--seed").value_or(1));
  params.photometry.bit_depth = args.integer("--bit-depth").value_or(8);
  params.pattern_set.projector_width = params.rig.projector.width;
  params.pattern_set.projector_height = params.rig.projector.height;
  params.validate();
  const std::string out = args.required("--out");
  const auto poses = simulation::writeCalibrationSequence(out, params);
  std::cerr << "rendered " << poses.size() << " board poses into " << out << "\n";
  return 0;
}

}  // namespace

int runSimulate(const std::vector<std::string>& raw) {
  if (!raw.empty() && raw[0] == "--list-parts") return listParts();
  if (std::find(raw.begin(), raw.end(), "--hand-eye") != raw.end()) return runSimulateHandEye(raw);
  if (raw.size() == 3 && raw[0] == "--export-part") {
    io::writeMesh(raw[2], simulation::makePart(raw[1]).mesh);
    return 0;
  }
  const Arguments args(raw,
                       {"--part", "--mesh", "--mesh-scale", "--objects", "--seed", "--out", "--bit-depth", "--threads",
                        "--calibration-board", "--poses", "--bin-length", "--bin-width", "--bin-wall-height",
                        "--camera-height", "--gripper", "--max-cycles", "--cup-diameter", "--tool-radius", "--stroke"},
                       {"--cloud-only", "--empty-bin"});
  if (args.value("--calibration-board")) return simulateCalibration(args);
  if (args.flag("--empty-bin")) return emptyBin(args);
  return simulatePile(args);
}

}  // namespace binpick::cli
