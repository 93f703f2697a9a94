// bench_emptying: does the cell empty its bins? For every part and gripper, several bins of parts
// emptied by the closed pick loop of the virtual cell (binpick/emptying/emptying.hpp): the share
// cleared, failed picks, cycles, the cell's cycle time (reconstruct + detect + plan; the rendering
// apart), and a plot of the parts left against the cycle.
//   bench_emptying [--parts a,b,...] [--meshes FILE[:SCALE],...] [--grippers suction,parallel]
//                  [--cups PART=M,...] [--noses PART=DEG,...] [--bins 5] [--objects 20] [--first-seed 1]
//                  [--threads 0] --out DIR
// --cups sets the suction cup's diameter (metres) for a part, as an integrator chooses the cup for
// the part's narrowest faces (the others get the cup picking/cup_choice.hpp chooses for them);
// --noses gives a part's suction tool a bent nose (degrees between the cup's axis and the body's).
// A value without PART= is every other part's.
// Writes DIR/emptying.md (the table, and why the parts left in each bin stayed), DIR/emptying.csv
// (one row per bin, flushed as it goes), DIR/emptying-parts-left.png; each bin's run
// (emptying.json, overlays) under DIR/emptying-runs/.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <thread>

#include "bench_support.hpp"
#include "binpick/core/error.hpp"
#include "binpick/core/stopwatch.hpp"
#include "binpick/emptying/emptying.hpp"
#include "binpick/io/geometry_io.hpp"
#include "binpick/picking/cup_choice.hpp"
#include "plot.hpp"

namespace binpick::bench {
namespace {

namespace fs = std::filesystem;

struct Options {
  std::vector<std::string> parts = simulation::partNames();
  std::vector<std::string> meshes;  // FILE[:SCALE]: parts the cell has never seen, without grasps
  std::vector<std::string> grippers = {"suction"};
  std::map<std::string, double> cups;   // part name -> cup diameter, metres
  std::map<std::string, double> noses;  // part name -> nose angle, degrees
  int bins = 5, objects = 20, first_seed = 1, threads = 0;
  std::string out;
};

constexpr const char* kUsage =
    "usage: bench_emptying [--parts a,b,...] [--meshes FILE[:SCALE],...] [--grippers suction,parallel]\n"
    "                      [--cups PART=M,...] [--noses PART=DEG,...] [--bins 5] [--objects 20]\n"
    "                      [--first-seed 1] [--threads 0] --out DIR\n";

// "l_bracket_long=0.004,gear=0.01" -> {l_bracket_long: 0.004, gear: 0.01}; "30" -> {"": 30}, every
// part's.
std::map<std::string, double> parsePartValues(const std::string& text) {
  std::map<std::string, double> values;
  for (const std::string& item : splitCommas(text)) {
    const auto equals = item.find('=');
    const std::string part = equals == std::string::npos ? "" : item.substr(0, equals);
    values[part] = std::stod(equals == std::string::npos ? item : item.substr(equals + 1));
  }
  return values;
}

// The part's own value, else every part's, if any.
std::optional<double> valueFor(const std::map<std::string, double>& values, const std::string& part) {
  for (const std::string& key : {part, std::string()}) {
    if (values.count(key)) return values.at(key);
  }
  return std::nullopt;
}

Options parseOptions(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string key = argv[i];
    if (key == "--help") {
      std::cout << kUsage;
      std::exit(0);
    }
    if (i + 1 >= argc) throw core::Error("option " + key + " needs a value\n" + kUsage);
    const std::string value = argv[++i];
    if (key == "--parts")
      options.parts = splitCommas(value);
    else if (key == "--meshes")
      options.meshes = splitCommas(value);
    else if (key == "--grippers")
      options.grippers = splitCommas(value);
    else if (key == "--cups")
      options.cups = parsePartValues(value);
    else if (key == "--noses")
      options.noses = parsePartValues(value);
    else if (key == "--bins")
      options.bins = std::stoi(value);
    else if (key == "--objects")
      options.objects = std::stoi(value);
    else if (key == "--first-seed")
      options.first_seed = std::stoi(value);
    else if (key == "--threads")
      options.threads = std::stoi(value);
    else if (key == "--out")
      options.out = value;
    else
      throw core::Error("unknown option " + key + "\n" + kUsage);
  }
  if (options.out.empty()) throw core::Error(std::string("--out is needed\n") + kUsage);
  if (options.bins < 1 || options.objects < 1) throw core::Error("--bins and --objects must be >= 1");
  return options;
}

struct Row {
  std::string part, gripper;
  int seed = 0;
  double cup_mm = 0.0;    // suction cup diameter; 0 for jaws
  double nose_deg = 0.0;  // suction tool's bent nose; 0 for a straight tool
  emptying::EmptyingReport report;
};

std::string csvLine(const Row& row) {
  const emptying::EmptyingReport& r = row.report;
  char text[256];
  std::snprintf(text, sizeof(text), "%s,%s,%.1f,%.0f,%d,%d,%d,%d,%zu,%s,%.1f,%.1f,%d\n", row.part.c_str(),
                row.gripper.c_str(), row.cup_mm, row.nose_deg, row.seed, r.objects, r.picked, r.failed_picks,
                r.cycles.size(), emptyingEndName(r.end).c_str(), r.median_cycle_ms, r.max_cycle_ms, r.grasps);
  return text;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// One table row per part and gripper: the means over its bins.
std::string summaryTable(const std::vector<Row>& rows) {
  std::map<std::pair<std::string, std::string>, std::vector<const Row*>> groups;
  std::vector<std::pair<std::string, std::string>> order;
  for (const Row& row : rows) {
    const auto key = std::make_pair(row.part, row.gripper);
    if (!groups.count(key)) order.push_back(key);
    groups[key].push_back(&row);
  }
  std::string table =
      "| part | gripper | cup | bins | cleared | bins with 0 failed picks | failed picks | cycles | median cycle | "
      "max cycle | grasps |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& key : order) {
    const auto& group = groups[key];
    int picked = 0, objects = 0, failed = 0, clean_bins = 0, cycles = 0, grasps = 0;
    std::vector<double> cycle_ms;
    double max_ms = 0.0;
    for (const Row* row : group) {
      picked += row->report.picked;
      objects += row->report.objects;
      failed += row->report.failed_picks;
      clean_bins += row->report.failed_picks == 0 ? 1 : 0;
      cycles += static_cast<int>(row->report.cycles.size());
      grasps = row->report.grasps;
      for (const auto& c : row->report.cycles) {
        if (c.cycle_ms > 0) cycle_ms.push_back(c.cycle_ms);
      }
      max_ms = std::max(max_ms, row->report.max_cycle_ms);
    }
    char cup[32] = "-";
    if (group.front()->cup_mm > 0) std::snprintf(cup, sizeof(cup), "%.0f mm", group.front()->cup_mm);
    if (group.front()->nose_deg > 0) {
      std::snprintf(cup + std::strlen(cup), sizeof(cup) - std::strlen(cup), ", %.0f deg nose", group.front()->nose_deg);
    }
    char line[320];
    std::snprintf(line, sizeof(line),
                  "| %s | %s | %s | %zu | %.1f%% (%d/%d) | %d/%zu | %d | %.1f | %.2f s | %.2f s | %d |\n",
                  key.first.c_str(), key.second.c_str(), cup, group.size(), 100.0 * picked / std::max(objects, 1),
                  picked, objects, clean_bins, group.size(), failed, static_cast<double>(cycles) / group.size(),
                  median(cycle_ms) / 1000.0, max_ms / 1000.0, grasps);
    table += line;
  }
  return table;
}

// Why the parts left stayed, one row per bin that kept any: how many lie near a wall (where the
// tool body meets the wall first), how many the cell did not detect in its last capture, and its
// last answer, which accounts for every part it detected (too tilted, tool hitting the bin, ...).
std::string partsLeftTable(const std::vector<Row>& rows) {
  constexpr double kNearWall = 0.05;  // metres from the part's centre to the wall
  std::string table =
      "| part | gripper | seed | left | within 5 cm of a wall | not detected | the cell's last answer |\n"
      "|---|---|---:|---:|---:|---:|---|\n";
  int bins = 0;
  for (const Row& row : rows) {
    const auto& left = row.report.left;
    if (left.empty() || row.report.cycles.empty()) continue;
    ++bins;
    const auto near_wall = std::count_if(
        left.begin(), left.end(), [&](const emptying::PartLeft& part) { return part.wall_distance < kNearWall; });
    const emptying::CycleRecord& last = row.report.cycles.back();
    const int undetected = std::max(0, static_cast<int>(left.size()) - last.detections);
    table += "| " + row.part + " | " + row.gripper + " | " + std::to_string(row.seed) + " | " +
             std::to_string(left.size()) + " | " + std::to_string(near_wall) + " | " + std::to_string(undetected) +
             " | " + last.status + (last.detail.empty() ? "" : ": " + last.detail) + " |\n";
  }
  return bins > 0 ? table : "Every bin was emptied.\n";
}

// Parts left in the bin after each cycle, one line per part and gripper (the mean over its bins;
// a bin that has ended counts with what it left).
void writePartsLeftPlot(const std::string& path, const std::vector<Row>& rows) {
  std::map<std::pair<std::string, std::string>, std::vector<std::vector<double>>> curves;
  std::vector<std::pair<std::string, std::string>> order;
  for (const Row& row : rows) {
    std::vector<double> left{static_cast<double>(row.report.objects)};
    for (const auto& cycle : row.report.cycles) left.push_back(cycle.parts_after);
    const auto key = std::make_pair(row.part, row.gripper);
    if (!curves.count(key)) order.push_back(key);
    curves[key].push_back(left);
  }
  LinePlot plot;
  plot.title = "Parts left in the bin (mean over the bins)";
  plot.x_label = "cycle";
  plot.y_label = "parts left";
  for (const auto& key : order) {
    const auto& bins = curves[key];
    std::size_t longest = 0;
    for (const auto& c : bins) longest = std::max(longest, c.size());
    PlotSeries series;
    series.label = key.first + (key.second == "suction" ? "" : " (" + key.second + ")");
    for (std::size_t k = 0; k < longest; ++k) {
      double sum = 0.0;
      for (const auto& c : bins) sum += k < c.size() ? c[k] : c.back();
      series.x.push_back(static_cast<double>(k));
      series.y.push_back(sum / bins.size());
    }
    plot.series.push_back(series);
  }
  writeLinePlot(path, plot);
}

std::string cpuName() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "unknown CPU";
}

void writeReport(const Options& options, const std::vector<Row>& rows, const std::vector<std::string>& cup_notes,
                 const std::string& command, double minutes) {
  std::ofstream md(fs::path(options.out) / "emptying.md");
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof(date), "%Y-%m-%d", std::gmtime(&now));
  md << "# Bin emptying in the virtual cell\n\n"
     << "`" << command << "`, " << date << ", " << std::thread::hardware_concurrency() << " threads, " << cpuName()
     << "; " << static_cast<int>(minutes + 0.5) << " minutes.\n\n"
     << summaryTable(rows) << "\n"
     << "cleared: parts the simulated robot took out of the bin / parts in the bin after the drop; a failed pick\n"
     << "is a pick the judge refused (the cell avoided that part afterwards). Cycle times: reconstruct + detect +\n"
     << "plan as binpickd timed them. Per bin: emptying.csv; plot: emptying-parts-left.png.\n\n"
     << "## Why the parts left stayed\n\n"
     << partsLeftTable(rows);
  if (cup_notes.empty()) return;
  const picking::CupChoiceParams choice;
  md << "\n## The cups chosen\n\n"
     << "Parts without --cups got the cup chooseCup finds (picking/cup_choice.hpp): the default "
     << 1000.0 * picking::GripperParams().cup_diameter << " mm cup unless a\nsmaller one lets at least "
     << 100.0 * choice.min_gain << "% more of the part's orientations show a grasp facing up.\n\n";
  for (const std::string& note : cup_notes) md << "- " << note << "\n";
}

// The gripper a part's bins run with: --cups and --noses where given; else, for suction, the cup
// chooseCup finds for the part (its choice noted for the report).
picking::GripperParams gripperFor(const simulation::Part& part, const std::string& type, const Options& options,
                                  std::vector<std::string>& cup_notes) {
  picking::GripperParams gripper;
  gripper.type = picking::gripperTypeFromName(type);
  if (gripper.type != picking::GripperType::Suction) return gripper;
  gripper.nose_angle_deg = valueFor(options.noses, part.name).value_or(0.0);
  if (const std::optional<double> cup = valueFor(options.cups, part.name)) {
    gripper.cup_diameter = *cup;
    return gripper;
  }
  const picking::CupChoice choice = picking::chooseCup(part.mesh, gripper, part.symmetry, {});
  gripper.cup_diameter = choice.diameter;
  cup_notes.push_back(part.name + ": " + picking::describeCupChoice(choice));
  std::cout << cup_notes.back() << std::endl;
  return gripper;
}

int run(int argc, char** argv) {
  const Options options = parseOptions(argc, argv);
  fs::create_directories(options.out);
  std::string command = "bench_emptying";
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
  const core::Stopwatch stopwatch;

  std::vector<simulation::Part> parts;
  for (const std::string& name : options.parts) parts.push_back(simulation::makePart(name));
  for (const std::string& spec : options.meshes) parts.push_back(bench::meshPart(spec));

  std::ofstream csv(fs::path(options.out) / "emptying.csv");
  csv << "part,gripper,cup_mm,nose_deg,seed,objects,picked,failed_picks,cycles,end,median_cycle_ms,max_cycle_ms,"
         "grasps\n";
  std::vector<Row> rows;
  std::vector<std::string> cup_notes;
  for (const simulation::Part& part : parts) {
    for (const std::string& gripper : options.grippers) {
      const picking::GripperParams tool = gripperFor(part, gripper, options, cup_notes);
      for (int b = 0; b < options.bins; ++b) {
        Row row{part.name, gripper, options.first_seed + b, 0.0, 0.0, {}};
        emptying::EmptyingParams params;
        params.pile.objects = options.objects;
        params.pile.seed = static_cast<uint64_t>(row.seed);
        params.pile.threads = options.threads;
        params.photometry.seed = params.pile.seed;
        params.photometry.threads = options.threads;
        params.gripper = tool;
        if (params.gripper.type == picking::GripperType::Suction) {
          row.cup_mm = 1000.0 * params.gripper.cup_diameter;
          row.nose_deg = params.gripper.nose_angle_deg;
        }
        const fs::path run_dir =
            fs::path(options.out) / "emptying-runs" / (part.name + "-" + gripper + "-" + std::to_string(row.seed));
        fs::remove_all(run_dir);
        params.out_directory = run_dir.string();
        try {
          row.report = emptying::emptyBin(part, params);
        } catch (const std::exception& e) {  // one bin that cannot run is reported; the rest go on
          std::cerr << part.name << " " << gripper << " seed " << row.seed << ": " << e.what() << "\n";
          continue;
        }
        std::cout << part.name << " " << gripper << " seed " << row.seed << ": " << emptying::summaryLine(row.report)
                  << std::endl;
        csv << csvLine(row) << std::flush;
        rows.push_back(std::move(row));
      }
    }
  }
  if (rows.empty()) throw core::Error("no bin could be run");
  writePartsLeftPlot((fs::path(options.out) / "emptying-parts-left.png").string(), rows);
  const double minutes = stopwatch.elapsedMs() / 60000.0;
  writeReport(options, rows, cup_notes, command, minutes);
  std::cout << summaryTable(rows);
  return 0;
}

}  // namespace
}  // namespace binpick::bench

int main(int argc, char** argv) {
  try {
    return binpick::bench::run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "bench_emptying: " << e.what() << "\n";
    return 1;
  }
}
