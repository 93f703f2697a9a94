// binpick evaluate --result result.json --truth CAPTURE_DIR: `binpick evaluate --help`.
// (--truth may also name truth/objects.json; the part defaults to the one the pile was made of)
// Scores a detect result against a simulated pile's truth with the paper's criterion
// (diam(M)/10 and 10 degrees, symmetry-aware; repeats count as wrong).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "arguments.hpp"
#include "binpick/core/error.hpp"
#include "binpick/core/json_fields.hpp"
#include "binpick/evaluation/evaluation.hpp"
#include "binpick/io/geometry_io.hpp"
#include "binpick/simulation/pile_truth.hpp"
#include "commands.hpp"

namespace binpick::cli {
namespace {

// The largest distance between two points of a mesh is attained at two of its vertices.
double meshDiameter(const io::TriangleMesh& mesh) {
  double best = 0.0;
  for (std::size_t a = 0; a < mesh.vertices.size(); ++a)
    for (std::size_t b = a + 1; b < mesh.vertices.size(); ++b)
      best = std::max(best, static_cast<double>((mesh.vertices[a] - mesh.vertices[b]).norm()));
  return best;
}

// A built-in part by name, else the mesh stored with the truth (a user's part: its symmetry found
// from the mesh).
simulation::Part partOf(const std::string& name, const std::string& truth_path) {
  const auto names = simulation::partNames();
  if (std::find(names.begin(), names.end(), name) != names.end()) return simulation::makePart(name);
  const std::filesystem::path truth_dir = std::filesystem::is_directory(truth_path)
                                              ? std::filesystem::path(truth_path) / "truth"
                                              : std::filesystem::path(truth_path).parent_path();
  return simulation::partFromMesh(name, io::readMesh((truth_dir / "part.ply").string()));
}

int run(const Arguments& args) {
  const std::string result_path = args.required("--result"), truth_path = args.required("--truth");
  const nlohmann::json result = core::readJsonFile(result_path);
  const simulation::PileTruth truth = simulation::readPileTruth(truth_path);
  const simulation::Part part = partOf(args.value("--part").value_or(truth.part), truth_path);

  std::vector<estimation::Detection> detections;
  for (const auto& d : result.value("detections", nlohmann::json::array())) {
    estimation::Detection detection;
    detection.T_camera_model = core::poseFromRows(d.value("pose", nlohmann::json()), result_path, "pose").cast<float>();
    detection.score = d.value("score", 0.0f);
    detection.coverage = d.value("coverage", 0.0f);
    detections.push_back(detection);
  }
  const std::vector<simulation::ObjectTruth>& objects = truth.objects;
  const double diameter = meshDiameter(part.mesh);
  const evaluation::Score score = evaluation::scoreDetections(
      detections, objects, part.symmetry, {diameter / 10.0, 10.0}, args.number("--min-visible").value_or(0.5));
  for (std::size_t d = 0; d < detections.size(); ++d) {
    const int o = score.matched_object[d];
    std::printf("detection %2zu  score %.3f  coverage %.2f  %s", d, detections[d].score, detections[d].coverage,
                o >= 0 ? "correct" : "WRONG");
    if (o >= 0) {
      const simulation::PoseError e =
          simulation::poseError(detections[d].T_camera_model.cast<double>(), objects[o].T_camera_object, part.symmetry);
      std::printf("  object %2d (%.0f%% visible)  error %.2f mm %.2f deg", o, 100.0 * objects[o].visible_fraction,
                  1000.0 * e.translation, e.rotation_deg);
    }
    std::printf("\n");
  }
  std::printf("found %d of %d objects at least half visible; %d correct, %d wrong (%d in the first 10)\n", score.found,
              score.findable, score.correct, score.wrong, score.wrong_in_first_10);
  return 0;
}

}  // namespace

void addEvaluateCommand(CLI::App& program, CommandTable& table) {
  CLI::App& command = table.add(program, "evaluate", "Score a detect result against a simulated pile's truth", run);
  addText(command, "--result", "FILE", "The result JSON of binpick detect")->required();
  addText(command, "--truth", "DIR", "The simulated capture directory (or its truth/objects.json)")->required();
  addText(command, "--part", "NAME", "A built-in part, or the truth's own part.ply (default: the pile's part)");
  addNumber(command, "--min-visible", "FRACTION", "Objects at least this visible must be found (default 0.5)");
}

}  // namespace binpick::cli
