#include "paper_figures.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "plot.hpp"

namespace binpick::bench {
namespace {

std::string format(const char* spec, double value) {
  char text[64];
  std::snprintf(text, sizeof text, spec, value);
  return text;
}

// Mean over the curves at each pick count that every curve reached.
std::vector<double> meanCurve(const std::vector<std::pair<std::string, SelectionCurves>>& curves,
                              std::vector<double> SelectionCurves::*member) {
  std::size_t n = curves.empty() ? 0 : (curves.front().second.*member).size();
  for (const auto& c : curves) n = std::min(n, (c.second.*member).size());
  std::vector<double> mean(n, 0.0);
  for (const auto& c : curves) {
    for (std::size_t k = 0; k < n; ++k) mean[k] += (c.second.*member)[k] / static_cast<double>(curves.size());
  }
  return mean;
}

PlotSeries series(const std::string& label, const std::vector<double>& y) {
  PlotSeries s;
  s.label = label;
  s.y = y;
  for (std::size_t k = 0; k < y.size(); ++k) s.x.push_back(static_cast<double>(k + 1));
  return s;
}

std::string image(const std::string& file, const std::string& alt) { return "![" + alt + "](" + file + ")\n\n"; }

double lastOr0(const std::vector<double>& v) { return v.empty() ? 0.0 : v.back(); }

PlotSeries scalingSeries(const std::string& label, const std::vector<ScalingPoint>& points, double ScalingPoint::*y) {
  PlotSeries s;
  s.label = label;
  for (const ScalingPoint& p : points) {
    s.x.push_back(p.x);
    s.y.push_back(p.*y);
  }
  return s;
}

std::string scalingRows(const std::vector<ScalingPoint>& points) {
  std::ostringstream out;
  for (const ScalingPoint& p : points) {
    out << "| " << p.label << " | " << format("%.0f", p.input_points) << " | " << format("%.0f", p.scene_points)
        << " | " << format("%.0f", p.ms_scene_preparation) << " | " << format("%.0f", p.ms_per_scene) << " | "
        << format("%.1f", p.ms_per_object) << " | " << format("%.1f%%", 100.0 * p.recognition) << " |\n";
  }
  return out.str();
}

const char* const kScalingHeader =
    "| setting | input points | subsampled scene points | scene preparation ms | ms / scene | ms / object "
    "| recognition |\n|---|---:|---:|---:|---:|---:|---:|\n";

}  // namespace

std::string selectionSection(const std::vector<std::pair<std::string, SelectionCurves>>& curves,
                             const std::filesystem::path& dir) {
  LinePlot plot;
  plot.title = "Multiple selection time against detections (mean over parts)";
  plot.x_label = "detections";
  plot.y_label = "cumulative selection time (ms)";
  plot.log_y = true;
  plot.series = {series("Algorithm 1 (binpick)", meanCurve(curves, &SelectionCurves::algorithm1_ms)),
                 series("eq. 4 for every candidate", meanCurve(curves, &SelectionCurves::rescore_all_ms)),
                 series("verify every candidate again", meanCurve(curves, &SelectionCurves::reverify_all_ms))};
  writeLinePlot((dir / "selection_time.png").string(), plot);

  std::ostringstream out;
  out << "## Multiple selection time against detections (the paper's Figure 5)\n\n"
      << "On each part's first scene (exact cloud), the verified candidates are picked one by one while the "
         "picked poses' scene points stop existing. All three strategies pick the same poses; one thread, ICP "
         "not included.\n\n"
      << image("selection_time.png", "selection time against detections")
      << "| part | scene points | candidates | picks | Algorithm 1 ms | eq. 4 for all ms | verify all again ms |\n"
         "|---|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& [part, c] : curves) {
    out << "| " << part << " | " << c.scene_points << " | " << c.candidates << " | " << c.algorithm1_ms.size() << " | "
        << format("%.2f", lastOr0(c.algorithm1_ms)) << " | " << format("%.2f", lastOr0(c.rescore_all_ms)) << " | "
        << format("%.1f", lastOr0(c.reverify_all_ms)) << " |\n";
  }
  return out.str() + "\n";
}

std::string scalingSection(const std::string& part, const ScalingResults& r, const std::filesystem::path& dir) {
  LinePlot points;
  points.title = "binpick time against scene points (" + part + ", 20 objects)";
  points.x_label = "finite points in the bin";
  points.y_label = "ms per scene";
  points.log_x = true;
  points.series = {scalingSeries("whole cloud", r.points_full, &ScalingPoint::ms_per_scene),
                   scalingSeries("cloud decimated 2x2 first", r.points_decimated, &ScalingPoint::ms_per_scene)};
  writeLinePlot((dir / "scaling_points.png").string(), points);

  LinePlot objects;
  objects.title = "binpick time against objects in the bin (" + part + ")";
  objects.x_label = "objects in the bin";
  objects.y_label = "ms";
  objects.series = {scalingSeries("per scene", r.objects, &ScalingPoint::ms_per_scene),
                    scalingSeries("per object x 10", r.objects, &ScalingPoint::ms_per_object)};
  for (double& y : objects.series[1].y) y *= 10.0;
  writeLinePlot((dir / "scaling_objects.png").string(), objects);

  LinePlot threads;
  threads.title = "binpick time against threads (" + part + ", 20 objects)";
  threads.x_label = "threads";
  threads.y_label = "ms per scene";
  threads.series = {scalingSeries("ms per scene", r.threads, &ScalingPoint::ms_per_scene)};
  writeLinePlot((dir / "scaling_threads.png").string(), threads);

  std::ostringstream out;
  out << "## Scaling (binpick, " << part << ", exact cloud)\n\n"
      << "### Scene points\n\nCamera resolution from 640x512 to 2448x2048 (same field of view); the cloud "
         "given whole, or decimated to every second pixel of every second row first (decimation timed).\n\n"
      << image("scaling_points.png", "time against scene points") << kScalingHeader << scalingRows(r.points_full)
      << scalingRows(r.points_decimated) << "\n### Objects in the bin\n\n"
      << image("scaling_objects.png", "time against objects") << kScalingHeader << scalingRows(r.objects)
      << "\n### Threads\n\n"
      << image("scaling_threads.png", "time against threads") << kScalingHeader << scalingRows(r.threads) << '\n';
  return out.str();
}

std::string cpuName() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "an unknown processor";
}

}  // namespace binpick::bench
