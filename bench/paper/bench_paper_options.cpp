#include "bench_paper_options.hpp"

#include <algorithm>

#include "bench_support.hpp"
#include "binpick/core/error.hpp"
#include "binpick/simulation/parts.hpp"

namespace binpick::bench {
namespace {

const std::vector<std::string> kMethods{"binpick", "ppf5", "ppf1", "opencv_ppf", "pcl_ppf"};
const std::vector<std::string> kSections{"paper", "selection", "scaling"};

bool contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

std::vector<std::string> checkedList(const std::string& option, const std::string& value,
                                     const std::vector<std::string>& allowed) {
  const std::vector<std::string> items = splitCommas(value);
  if (items.empty()) throw core::Error(option + " needs at least one item");
  for (const std::string& item : items) {
    if (allowed.empty() || contains(allowed, item)) continue;
    std::string known;
    for (const std::string& a : allowed) known += (known.empty() ? "" : ", ") + a;
    throw core::Error(option + ": '" + item + "' is unknown (" + known + ")");
  }
  return items;
}

std::vector<CloudInput> inputsFrom(const std::string& value) {
  std::vector<CloudInput> inputs;
  for (const std::string& name : checkedList("--inputs", value, {"exact", "reconstructed"})) {
    inputs.push_back(name == "exact" ? CloudInput::Exact : CloudInput::Reconstructed);
  }
  return inputs;
}

int positive(const std::string& option, const std::string& value) {
  const int n = std::stoi(value);
  if (n < 1) throw core::Error(option + " must be >= 1");
  return n;
}

}  // namespace

const char* paperBenchUsage() {
  return "bench_paper [options]: the paper's synthetic experiment, Figure 5 and scaling on the virtual cell\n"
         "  --scenes N            scenes per part (default 2; the paper: 50)\n"
         "  --parts A,B           parts (default the paper's six: gear, l_bracket, l_bracket_long,\n"
         "                        ring_magnet, switch, bulge)\n"
         "  --methods A,B         binpick, ppf5, ppf1, opencv_ppf, pcl_ppf (default all)\n"
         "  --inputs A,B          exact, reconstructed (default both)\n"
         "  --sections A,B        paper, selection, scaling (default all)\n"
         "  --peer-scenes K       OpenCV and PCL on the first K scenes of a part only (default 1)\n"
         "  --peer-parts A,B      and on these parts only (default every part)\n"
         "  --objects N           objects per scene (default 20)\n"
         "  --seed S              scene s of every part has seed S + s (default 1)\n"
         "  --threads N           0: all hardware threads (default)\n"
         "  --scaling-part NAME   the part of the scaling runs (default l_bracket)\n"
         "  --scaling-scenes N    scenes per scaling setting (default 2)\n"
         "  --out DIR             results.md, outcomes.csv and the PNG plots (default docs/benchmark)\n"
         "  --settings FILE       binpick's detector settings, a detection.yaml (default: the defaults)\n"
         "  --reconstruction-settings FILE\n"
         "                        the reconstructed input's settings, a file with a `reconstruction:`\n"
         "                        section (default: the defaults)\n"
         "  --explain             binpick's detections, one line each: right or wrong, score, coverage,\n"
         "                        seen-through share, twin margin (on stderr)\n";
}

bool PaperBenchOptions::has(const std::string& section) const { return contains(sections, section); }

bool PaperBenchOptions::runsPeersOn(const std::string& part) const {
  return peer_parts.empty() || contains(peer_parts, part);
}

PaperBenchOptions parsePaperBenchOptions(int argc, char** argv) {
  PaperBenchOptions o;
  const std::vector<std::string> parts = simulation::partNames();
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--help" || flag == "-h") {
      o.help = true;
      continue;
    }
    if (flag == "--explain") {
      o.explain = true;
      continue;
    }
    if (i + 1 >= argc) throw core::Error(flag + " needs a value");
    const std::string value = argv[++i];
    try {
      if (flag == "--scenes")
        o.scenes = positive(flag, value);
      else if (flag == "--peer-scenes")
        o.peer_scenes = positive(flag, value);
      else if (flag == "--peer-parts")
        o.peer_parts = checkedList(flag, value, parts);
      else if (flag == "--objects")
        o.objects = positive(flag, value);
      else if (flag == "--seed")
        o.seed = std::stoull(value);
      else if (flag == "--threads")
        o.threads = std::max(0, std::stoi(value));
      else if (flag == "--parts")
        o.parts = checkedList(flag, value, parts);
      else if (flag == "--methods")
        o.methods = checkedList(flag, value, kMethods);
      else if (flag == "--inputs")
        o.inputs = inputsFrom(value);
      else if (flag == "--sections")
        o.sections = checkedList(flag, value, kSections);
      else if (flag == "--scaling-part")
        o.scaling_part = checkedList(flag, value, parts).front();
      else if (flag == "--scaling-scenes")
        o.scaling_scenes = positive(flag, value);
      else if (flag == "--out")
        o.out = value;
      else if (flag == "--settings")
        o.settings = value;
      else if (flag == "--reconstruction-settings")
        o.reconstruction_settings = value;
      else
        throw core::Error("unknown option " + flag);
    } catch (const std::logic_error&) {  // std::stoi and friends
      throw core::Error(flag + ": '" + value + "' is not a number");
    }
  }
  return o;
}

}  // namespace binpick::bench
