// binpick simulate: a pile (capture or --cloud-only cloud), --empty-bin, --calibration-board,
// --hand-eye (simulate_hand_eye.hpp), --list-parts or --export-part NAME FILE; each mode refuses
// the options of the others. `binpick simulate --help` lists them.
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
#include "binpick/picking/cup_choice.hpp"
#include "binpick/simulation/calibration_sequence.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/pile.hpp"
#include "binpick/simulation/pile_truth.hpp"
#include "commands.hpp"
#include "gripper_options.hpp"
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

// A built-in part, or a user's mesh file (its symmetry found from the mesh, and printed).
simulation::Part partFrom(const Arguments& args) {
  if (!args.value("--part") && !args.value("--mesh")) throw missingOption("--part or --mesh");
  if (args.value("--part")) return simulation::makePart(*args.value("--part"));
  const std::string file = args.required("--mesh");
  io::TriangleMesh mesh = io::readMesh(file);
  const double scale = args.number("--mesh-scale").value_or(1.0);
  if (!(scale > 0.0)) throw core::Error("--mesh-scale must be positive");
  for (auto& v : mesh.vertices) v *= static_cast<float>(scale);
  simulation::Part part = simulation::partFromMesh(file, std::move(mesh));
  std::cerr << file << ": " << part.description << "\n";
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
  params.gripper = gripperFromArguments(args);
  if (params.gripper.type == picking::GripperType::Suction && !args.value("--cup-diameter")) {
    // No cup given: the one an integrator would choose for the part, said before the run.
    const picking::CupChoice choice = picking::chooseCup(part.mesh, params.gripper, part.symmetry, {});
    params.gripper.cup_diameter = choice.diameter;
    std::cout << "cup: " << picking::describeCupChoice(choice) << "; --cup-diameter sets one" << std::endl;
  }
  params.max_cycles = args.integer("--max-cycles").value_or(0);
  params.web_port = args.integer("--web-port").value_or(-1);
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

int exportPart(const Arguments& args) {
  const std::vector<std::string> name_and_file = args.values("--export-part");
  io::writeMesh(name_and_file.at(1), simulation::makePart(name_and_file.at(0)).mesh);
  return 0;
}

int run(const Arguments& args) {
  if (args.flag("--list-parts")) return listParts();
  if (args.value("--export-part")) return exportPart(args);
  args.required("--out");  // before any work
  if (args.value("--hand-eye")) return simulateHandEye(args);
  if (args.value("--calibration-board")) return simulateCalibration(args);
  if (args.flag("--empty-bin")) return emptyBin(args);
  return simulatePile(args);
}

// The options of a pile, in the pile and the bin-emptying modes.
std::vector<CLI::Option*> addPileOptions(CLI::App& command) {
  CLI::Option* part = addText(command, "--part", "NAME", "A built-in part (see --list-parts)");
  CLI::Option* mesh = addText(command, "--mesh", "FILE", "A mesh file (PLY, STL, OBJ) to pile instead");
  part->excludes(mesh);
  std::vector<CLI::Option*> options = {
      part, mesh,
      addNumber(command, "--mesh-scale", "S", "Scale the mesh by S, e.g. 0.001 for mm (default 1)")->needs(mesh),
      addInteger(command, "--objects", "N", "Parts dropped into the bin (default 20)"),
      addInteger(command, "--threads", "N", "Threads (default 0: all cores)")};
  CLI::Option_group& bin = *command.add_option_group("Bin options");
  addNumber(bin, "--bin-length", "M", "Inner length of the bin in metres (default 0.40)");
  addNumber(bin, "--bin-width", "M", "Inner width of the bin in metres (default 0.30)");
  addNumber(bin, "--bin-wall-height", "M", "Height of the bin's walls in metres (default 0.15)");
  addNumber(bin, "--camera-height", "M", "Camera above the bin floor in metres (default 0.90)");
  for (CLI::Option* option : optionsOf(bin)) options.push_back(option);
  return options;
}

// The gripper and the loop of --empty-bin.
void addEmptyBinOptions(CLI::App& command, CLI::Option* empty_bin) {
  for (CLI::Option* option : addGripperOptions(command, "suction (default) or parallel")) option->needs(empty_bin);
  addInteger(command, "--max-cycles", "K", "Stop after K cycles (default 0: until the bin is empty)")->needs(empty_bin);
  addInteger(command, "--web-port", "N", "Serve the cell's web view on 127.0.0.1:N while the run lasts (default: none)")
      ->check(CLI::Range(0, 65535))
      ->needs(empty_bin);
}

}  // namespace

void addSimulateCommand(CLI::App& program, CommandTable& table) {
  CLI::App& command =
      table.add(program, "simulate", "Render the virtual cell: a pile, bin emptying, calibration views", run);
  const std::vector<CLI::Option*> pile = addPileOptions(command);
  CLI::Option* seed = addInteger(command, "--seed", "S", "Random seed (default 1)");
  CLI::Option* out = addText(command, "--out", "DIR", "Write here (a new or empty directory for a pile)");
  CLI::Option* bit_depth = addInteger(command, "--bit-depth", "BITS", "Image bit depth: 8 (default) or 16");
  CLI::Option* cloud_only = addFlag(command, "--cloud-only", "Write the ideal cloud.ply instead of the images");

  CLI::Option* empty_bin = addFlag(command, "--empty-bin", "Run the closed pick loop until the bin is empty");
  addEmptyBinOptions(command, empty_bin);
  CLI::Option* board = addText(command, "--calibration-board", "TYPE", "Render views of a charuco or chessboard board");
  addInteger(command, "--poses", "K", "Board poses (default 10)")->needs(board);
  CLI::Option* hand_eye = addSimulateHandEyeOptions(command);
  CLI::Option* list = addFlag(command, "--list-parts", "List the built-in parts");
  CLI::Option* export_part = addText(command, "--export-part", "NAME FILE", "Write built-in part NAME's mesh to FILE");
  export_part->expected(2)->option_text("NAME FILE");

  refuseTogether({empty_bin, board, hand_eye, list, export_part}, {empty_bin, board, hand_eye, list, export_part});
  refuseTogether(pile, {board, hand_eye, list, export_part});
  refuseTogether({cloud_only}, {empty_bin, board, hand_eye, list, export_part});
  refuseTogether({bit_depth}, {empty_bin, hand_eye, list, export_part});
  refuseTogether({seed, out}, {list, export_part});
}

}  // namespace binpick::cli
