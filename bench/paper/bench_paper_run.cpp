#include "bench_paper_run.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "binpick/core/error.hpp"
#include "binpick/core/thread_count.hpp"
#include "binpick/reconstruction/reconstruction_config.hpp"
#include "binpick_method.hpp"
#include "experiment.hpp"
#include "opencv_ppf_method.hpp"
#include "paper_figures.hpp"
#include "pcl_ppf_method.hpp"
#include "report.hpp"
#include "scaling.hpp"
#include "selection_timing.hpp"

namespace binpick::bench {
namespace {

std::unique_ptr<PoseMethod> makeMethod(const std::string& name, const MethodSetup& setup) {
  if (isBinpickMethod(name)) return makeBinpickMethod(name, setup);
  if (name == "opencv_ppf") return std::make_unique<OpenCvPpfMethod>(setup);
  if (name == "pcl_ppf") return std::make_unique<PclPpfMethod>(setup);
  throw core::Error("unknown method " + name);
}

bool isPeer(const std::string& method) { return !isBinpickMethod(method); }

std::string joined(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
  return text;
}

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  return text;
}

std::string commandLine(int argc, char** argv) {
  std::string line = "bench_paper";
  for (int i = 1; i < argc; ++i) line += std::string(" ") + argv[i];
  return line;
}

// What the scenes, the machine and the command were: results are only comparable with these.
std::string preamble(const PaperBenchOptions& o, int argc, char** argv) {
  std::ostringstream out;
  out << "# Benchmark results\n\n"
      << "Generated " << utcNow() << " by `" << commandLine(argc, argv) << "` with "
      << core::resolveThreadCount(o.threads) << " threads on " << cpuName() << ".\n\n"
      << "Scenes: " << o.scenes << " per part, " << o.objects << " objects each, seeds " << o.seed << ".."
      << o.seed + o.scenes - 1 << " (OpenCV's and PCL's matchers: the first " << o.peer_scenes
      << (o.peer_parts.empty() ? "" : ", on " + joined(o.peer_parts) + " only")
      << "), virtual rig 1280x1024; the same scenes for every method. "
      << "Correct: translation < diam/10 and rotation < 10 degrees (minimum over the part's symmetries); "
      << "a second detection of an object is wrong. Times: the whole process (normals, matching, "
      << "refinement), wall clock, per object in the bin.\n\n";
  return out.str();
}

struct ExperimentData {
  Tallies tallies;
  std::vector<std::pair<std::string, SelectionCurves>> selection;  // per part
  double reconstruct_ms = 0.0;                                     // summed over the scenes
  int reconstructed_scenes = 0;
};

// Every method on one scene and input. A method that fails is reported and skipped: one peer's
// exception must not lose the hours of results around it.
void runScene(const std::vector<std::unique_ptr<PoseMethod>>& methods, const BenchScene& scene, int scene_index,
              const simulation::Part& part, double diameter, const PaperBenchOptions& o, std::ofstream& csv,
              ExperimentData& data) {
  for (CloudInput input : o.inputs) {
    for (const auto& method : methods) {
      if (isPeer(method->name()) && scene_index >= o.peer_scenes) continue;
      const std::string what =
          part.name + " seed " + std::to_string(scene.params.seed) + " " + inputName(input) + " " + method->name();
      try {
        const SceneOutcome outcome = runMethod(*method, scene, input, part, diameter);
        writeOutcome(csv, outcome);
        csv.flush();
        data.tallies[{input, part.name, method->name()}].add(outcome);
        std::fprintf(stderr, "%s: %d/%d correct, %d detections (%d wrong in the first 10), %.0f ms\n", what.c_str(),
                     outcome.correct, outcome.objects, outcome.detections, outcome.wrong_in_first_10, outcome.ms);
        if (o.explain) {
          for (const std::string& line : outcome.explanation) std::fprintf(stderr, "  %s\n", line.c_str());
        }
      } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: FAILED, left out of the tables: %s\n", what.c_str(), e.what());
      }
    }
  }
}

void runPart(const PaperBenchOptions& o, const std::string& part_name, std::ofstream& csv, ExperimentData& data) {
  const simulation::Part part = simulation::makePart(part_name);
  const estimation::PreparedModel model = estimation::prepareModel(io::ModelGeometry{part.mesh, {}}, {});
  const MethodSetup setup{&model, o.objects, o.threads, o.settings};
  std::vector<std::unique_ptr<PoseMethod>> methods;
  if (o.has("paper")) {
    for (const std::string& name : o.methods) {
      if (isPeer(name) && !o.runsPeersOn(part_name)) continue;
      methods.push_back(makeMethod(name, setup));
    }
  }
  const bool reconstruct =
      o.has("paper") && std::find(o.inputs.begin(), o.inputs.end(), CloudInput::Reconstructed) != o.inputs.end();
  const reconstruction::ReconstructionParams reconstruction_params =
      o.reconstruction_settings.empty() ? reconstruction::ReconstructionParams{}
                                        : reconstruction::loadReconstructionParams(o.reconstruction_settings);
  for (int s = 0; s < o.scenes; ++s) {
    SceneRequest request;
    request.reconstruction = reconstruction_params;
    request.objects = o.objects;
    request.seed = o.seed + static_cast<uint64_t>(s);
    request.reconstruct = reconstruct;
    request.threads = o.threads;
    const BenchScene scene = makeBenchScene(part, request);
    if (reconstruct) {
      data.reconstruct_ms += scene.reconstruct_ms;
      ++data.reconstructed_scenes;
    }
    if (s == 0 && o.has("selection")) {
      data.selection.emplace_back(part_name,
                                  measureSelection(model, scene.truth.cloud, scene.crop, o.objects, o.threads));
    }
    runScene(methods, scene, s, part, model.diameter, o, csv, data);
  }
}

// The reconstruction's own time is not in the methods' figures: say what it adds.
std::string reconstructionNote(CloudInput input, const ExperimentData& data) {
  if (input != CloudInput::Reconstructed || data.reconstructed_scenes == 0) return "";
  char text[256];
  const double per_scene = data.reconstruct_ms / data.reconstructed_scenes;
  std::snprintf(text, sizeof text,
                "Reconstruction (decode, triangulate, filter; not included below) took %.0f ms per scene.\n\n",
                per_scene);
  return text;
}

std::string experimentSections(const PaperBenchOptions& o, const ExperimentData& data) {
  std::ostringstream out;
  for (CloudInput input : o.inputs) {
    const TableLayout layout{o.parts, o.methods, input};
    const std::string name = inputName(input) + " cloud";
    out << "## Recognition rate, " << name << " (the paper's Table II)\n\n"
        << recognitionTable(data.tallies, layout) << "\n## Speed in ms per object, " << name
        << " (the paper's Table III)\n\n"
        << reconstructionNote(input, data) << speedTable(data.tallies, layout) << "\n## Precision / recall, " << name
        << "\n\n"
        << "Precision: correct / detections. Recall: objects found / objects at least half visible.\n\n"
        << precisionRecallTable(data.tallies, layout) << "\n## Wrong detections among the first 10, " << name << "\n\n"
        << "Wrong detections among each scene's first 10 (what a robot picks first), in how many scenes.\n\n"
        << earlyWrongTable(data.tallies, layout) << "\n## Stages in ms per object, " << name << "\n\n"
        << stageTable(data.tallies, layout) << '\n';
  }
  return out.str();
}

}  // namespace

void runPaperBench(const PaperBenchOptions& o, int argc, char** argv) {
  std::filesystem::create_directories(o.out);
  const std::filesystem::path dir(o.out);
  std::ostringstream markdown;
  markdown << preamble(o, argc, argv);
  if (o.has("paper") || o.has("selection")) {
    std::ofstream csv(dir / "outcomes.csv");
    if (!csv) throw core::Error("cannot write " + (dir / "outcomes.csv").string());
    writeOutcomeHeader(csv);
    ExperimentData data;
    for (const std::string& part : o.parts) runPart(o, part, csv, data);
    if (o.has("paper")) markdown << experimentSections(o, data);
    if (o.has("selection")) markdown << selectionSection(data.selection, dir);
  }
  if (o.has("scaling")) {
    const simulation::Part part = simulation::makePart(o.scaling_part);
    const estimation::PreparedModel model = estimation::prepareModel(io::ModelGeometry{part.mesh, {}}, {});
    ScalingParams params;
    params.scenes = o.scaling_scenes;
    params.objects = o.objects;
    params.seed = o.seed;
    params.threads = o.threads;
    std::fprintf(stderr, "scaling on %s ...\n", o.scaling_part.c_str());
    markdown << scalingSection(o.scaling_part, measureScaling(part, model, params), dir);
  }
  std::ofstream results(dir / "results.md");
  results << markdown.str();
  if (!results) throw core::Error("cannot write " + (dir / "results.md").string());
  std::fprintf(stderr, "wrote %s\n", (dir / "results.md").c_str());
}

}  // namespace binpick::bench
