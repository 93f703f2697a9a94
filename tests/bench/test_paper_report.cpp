// The benchmark's tables (the layout of the paper's Tables II and III) and its command line.
#include <gtest/gtest.h>

#include <string>

#include "bench_paper_options.hpp"
#include "binpick/core/error.hpp"
#include "report.hpp"

namespace binpick::bench {
namespace {

SceneOutcome outcome(const std::string& part, const std::string& method, int correct, int detections, double ms) {
  SceneOutcome o;
  o.part = part;
  o.method = method;
  o.objects = 20;
  o.findable = 10;
  o.found = std::min(correct, 10);
  o.correct = correct;
  o.detections = detections;
  o.ms = ms;
  return o;
}

Tallies exampleTallies() {
  Tallies t;
  const auto add = [&t](const SceneOutcome& o) { t[{CloudInput::Exact, o.part, o.method}].add(o); };
  add(outcome("gear", "binpick", 16, 18, 400.0));   // 80%, 20 ms per object
  add(outcome("gear", "ppf5", 10, 20, 2000.0));     // 50%, 100 ms per object
  add(outcome("bulge", "binpick", 18, 20, 200.0));  // 90%, 10 ms per object
  return t;
}

const TableLayout kLayout{{"gear", "bulge"}, {"binpick", "ppf5"}, CloudInput::Exact};

TEST(PaperTables, RecognitionRatesPerPartAndTheirAverage) {
  const std::string table = recognitionTable(exampleTallies(), kLayout);
  EXPECT_NE(table.find("| part | binpick | ppf5 |"), std::string::npos) << table;
  EXPECT_NE(table.find("| gear | 80.0% | 50.0% |"), std::string::npos) << table;
  EXPECT_NE(table.find("| bulge | 90.0% | – |"), std::string::npos) << table;
  // The paper's average is over parts; a method missing a part averages the parts it has.
  EXPECT_NE(table.find("| **average** | **85.0%** | **50.0%** |"), std::string::npos) << table;
  EXPECT_NE(table.find("| scenes per part | 1 | 1 |"), std::string::npos) << table;
}

TEST(PaperTables, SpeedPerObjectWithTimeRelativeToTheFirstMethod) {
  const std::string table = speedTable(exampleTallies(), kLayout);
  EXPECT_NE(table.find("| gear | 20 | 100 |"), std::string::npos) << table;
  EXPECT_NE(table.find("| **average** | **15** | **100** |"), std::string::npos) << table;
  EXPECT_NE(table.find("| relative time | 1.00 | 6.67 |"), std::string::npos) << table;
}

TEST(PaperTables, PrecisionAndRecall) {
  const std::string table = precisionRecallTable(exampleTallies(), kLayout);
  EXPECT_NE(table.find("| gear | 88.9% / 100.0% | 50.0% / 100.0% |"), std::string::npos) << table;
}

std::string optionError(std::vector<std::string> args) {
  args.insert(args.begin(), "bench_paper");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  try {
    parsePaperBenchOptions(static_cast<int>(argv.size()), argv.data());
  } catch (const core::Error& e) {
    return e.what();
  }
  return "";
}

TEST(PaperBenchOptions, BadValuesAreNamed) {
  EXPECT_NE(optionError({"--methods", "binpick,halcon"}).find("'halcon' is unknown"), std::string::npos);
  EXPECT_NE(optionError({"--parts", "sprocket"}).find("'sprocket'"), std::string::npos);
  EXPECT_NE(optionError({"--scenes", "many"}).find("--scenes: 'many' is not a number"), std::string::npos);
  EXPECT_NE(optionError({"--scenes", "0"}).find("--scenes must be >= 1"), std::string::npos);
  EXPECT_NE(optionError({"--inputs", "photo"}).find("'photo'"), std::string::npos);
  EXPECT_NE(optionError({"--scenes"}).find("needs a value"), std::string::npos);
  EXPECT_EQ(optionError({"--scenes", "3", "--inputs", "exact"}), "");
}

TEST(PaperBenchOptions, PeerLimitsAndHelp) {
  std::vector<std::string> args{"bench_paper", "--peer-parts", "gear", "--peer-scenes", "3", "--help"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  const PaperBenchOptions o = parsePaperBenchOptions(static_cast<int>(argv.size()), argv.data());
  EXPECT_TRUE(o.help);
  EXPECT_EQ(o.peer_scenes, 3);
  EXPECT_TRUE(o.runsPeersOn("gear"));
  EXPECT_FALSE(o.runsPeersOn("bulge"));
  EXPECT_TRUE(PaperBenchOptions{}.runsPeersOn("bulge"));
}

}  // namespace
}  // namespace binpick::bench
