#include "report.hpp"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <sstream>

#include "binpick_method.hpp"

namespace binpick::bench {
namespace {

using Figure = std::function<double(const Tally&)>;
using Format = std::function<std::string(double)>;

std::string printf1(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

std::string percent(double fraction) { return printf1("%.1f%%", 100.0 * fraction); }
std::string milliseconds(double ms) { return printf1(ms < 10.0 ? "%.1f" : "%.0f", ms); }

const Tally* find(const Tallies& tallies, const TableLayout& layout, const std::string& part,
                  const std::string& method) {
  const auto it = tallies.find({layout.input, part, method});
  return it == tallies.end() || it->second.scenes == 0 ? nullptr : &it->second;
}

void headerRow(std::ostringstream& out, const std::string& first, const std::vector<std::string>& methods) {
  out << "| " << first << " |";
  for (const std::string& m : methods) out << ' ' << m << " |";
  out << "\n|---|";
  for (std::size_t i = 0; i < methods.size(); ++i) out << "---:|";
  out << '\n';
}

// The mean over the parts that have the method, as the paper averages its per-part figures.
double averageOverParts(const Tallies& tallies, const TableLayout& layout, const std::string& method,
                        const Figure& figure, int& parts_counted) {
  double sum = 0.0;
  parts_counted = 0;
  for (const std::string& part : layout.parts) {
    if (const Tally* t = find(tallies, layout, part, method)) {
      sum += figure(*t);
      ++parts_counted;
    }
  }
  return parts_counted ? sum / parts_counted : 0.0;
}

// The header and one row per part, each cell `cell` of the part's tally ("–" without one).
void partRows(std::ostringstream& out, const Tallies& tallies, const TableLayout& layout,
              const std::function<std::string(const Tally&)>& cell) {
  headerRow(out, "part", layout.methods);
  for (const std::string& part : layout.parts) {
    out << "| " << part << " |";
    for (const std::string& method : layout.methods) {
      const Tally* t = find(tallies, layout, part, method);
      out << ' ' << (t ? cell(*t) : "–") << " |";
    }
    out << '\n';
  }
}

std::string partsTable(const Tallies& tallies, const TableLayout& layout, const Figure& figure, const Format& format,
                       bool relative_row) {
  std::ostringstream out;
  partRows(out, tallies, layout, [&](const Tally& t) { return format(figure(t)); });
  std::vector<double> averages;
  out << "| **average** |";
  for (const std::string& method : layout.methods) {
    int counted = 0;
    averages.push_back(averageOverParts(tallies, layout, method, figure, counted));
    out << ' ' << (counted ? "**" + format(averages.back()) + "**" : "–") << " |";
  }
  out << '\n';
  if (relative_row && !averages.empty() && averages.front() > 0.0) {
    out << "| relative time |";
    for (double a : averages) out << ' ' << (a > 0.0 ? printf1("%.2f", a / averages.front()) : "–") << " |";
    out << '\n';
  }
  return out.str();
}

}  // namespace

// How many scenes each method ran per part (methods may run on fewer scenes than others).
std::string scenesRow(const Tallies& tallies, const TableLayout& layout) {
  std::ostringstream out;
  out << "| scenes per part |";
  for (const std::string& method : layout.methods) {
    int most = 0;
    for (const std::string& part : layout.parts) {
      if (const Tally* t = find(tallies, layout, part, method)) most = std::max(most, t->scenes);
    }
    out << ' ' << most << " |";
  }
  return out.str() + "\n";
}

std::string recognitionTable(const Tallies& tallies, const TableLayout& layout) {
  return partsTable(
             tallies, layout, [](const Tally& t) { return t.recognitionRate(); }, percent, false) +
         scenesRow(tallies, layout);
}

std::string speedTable(const Tallies& tallies, const TableLayout& layout) {
  return partsTable(
      tallies, layout, [](const Tally& t) { return t.msPerObject(); }, milliseconds, true);
}

std::string precisionRecallTable(const Tallies& tallies, const TableLayout& layout) {
  std::ostringstream out;
  partRows(out, tallies, layout, [](const Tally& t) { return percent(t.precision()) + " / " + percent(t.recall()); });
  return out.str();
}

std::string earlyWrongTable(const Tallies& tallies, const TableLayout& layout) {
  std::ostringstream out;
  partRows(out, tallies, layout, [](const Tally& t) {
    return std::to_string(t.wrong_in_first_10) + " in " + std::to_string(t.scenes_wrong_in_first_10) + " of " +
           std::to_string(t.scenes);
  });
  return out.str();
}

std::string stageTable(const Tallies& tallies, const TableLayout& layout) {
  std::ostringstream out;
  out << "| part | method | scene + normals | voting | verification | selection (Drost: clustering) | ICP | total |\n"
         "|---|---|---:|---:|---:|---:|---:|---:|\n";
  for (const std::string& part : layout.parts) {
    for (const std::string& method : layout.methods) {
      const Tally* t = find(tallies, layout, part, method);
      if (!t || !isBinpickMethod(method) || t->objects == 0) continue;
      const auto per_object = [&](double ms) { return milliseconds(ms / t->objects); };
      const estimation::StageTimings& s = t->stages;
      out << "| " << part << " | " << method << " | " << per_object(s.prepare_scene) << " | " << per_object(s.voting)
          << " | " << per_object(s.verification) << " | " << per_object(s.selection) << " | " << per_object(s.icp)
          << " | " << per_object(s.total) << " |\n";
    }
  }
  return out.str();
}

}  // namespace binpick::bench
