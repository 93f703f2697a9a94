// The closed pick loop on a small bin: the cell, its robot protocol and the judged picks together.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "binpick/core/error.hpp"
#include "binpick/emptying/emptying.hpp"
#include "temp_directory_test.hpp"

namespace binpick::emptying {
namespace {

class EmptyingTest : public test::TempDirectoryTest {};

EmptyingParams smallBin(const std::string& out, int objects, uint64_t seed) {
  EmptyingParams params;
  params.pile.objects = objects;
  params.pile.seed = seed;
  params.photometry.seed = seed;
  params.out_directory = out;
  return params;
}

TEST_F(EmptyingTest, FiveBracketsLeaveTheBinWithoutAFailedPick) {
  const simulation::Part part = simulation::makePart("l_bracket");
  std::vector<CycleRecord> seen;
  const EmptyingReport report =
      emptyBin(part, smallBin(pathOf("run"), 5, 4), [&](const CycleRecord& cycle) { seen.push_back(cycle); });

  EXPECT_EQ(report.objects, 5);
  EXPECT_GE(report.picked, 4) << summaryLine(report);
  EXPECT_EQ(report.failed_picks, 0) << summaryLine(report);
  EXPECT_GT(report.grasps, 0);
  ASSERT_EQ(seen.size(), report.cycles.size());
  // Every pick the judge accepted took a part out (a part the re-settling throws out goes too); a
  // cycle without one leaves the pile as it was.
  for (const CycleRecord& cycle : report.cycles) {
    const bool picked = cycle.pick && cycle.pick->ok;
    if (picked) {
      EXPECT_LE(cycle.parts_after, cycle.parts_before - 1) << cycleLine(cycle);
      EXPECT_TRUE(cycle.pick->T_base_part_true.has_value());
    } else {
      EXPECT_EQ(cycle.parts_after, cycle.parts_before) << cycleLine(cycle);
    }
  }
  if (report.picked + report.escaped == report.objects) {
    EXPECT_EQ(report.end, EmptyingEnd::Empty);
  }
  EXPECT_EQ(report.left.size(), static_cast<std::size_t>(report.objects - report.picked - report.escaped));
}

TEST_F(EmptyingTest, WritesTheReportAndTheCellsFiles) {
  const EmptyingReport report = emptyBin(simulation::makePart("l_bracket"), smallBin(pathOf("run"), 2, 7));
  std::ifstream file(pathOf("run/emptying.json"));
  ASSERT_TRUE(file.good());
  const nlohmann::json json = nlohmann::json::parse(file);
  EXPECT_EQ(json["objects"], report.objects);
  EXPECT_EQ(json["picked"], report.picked);
  EXPECT_EQ(json["failed_picks"], report.failed_picks);
  EXPECT_EQ(json["cycles"], static_cast<int>(report.cycles.size()));
  EXPECT_EQ(json["end"], emptyingEndName(report.end));
  EXPECT_TRUE(json["cycle_ms"].contains("median"));
  ASSERT_EQ(json["picks"].size(), static_cast<std::size_t>(report.picked + report.failed_picks));
  for (const auto& pick : json["picks"]) {
    EXPECT_TRUE(pick.contains("T_base_grasp"));
    EXPECT_TRUE(pick.contains("reason"));
  }
  EXPECT_TRUE(std::filesystem::exists(pathOf("run/cell/binpickd.yaml")));
  EXPECT_TRUE(std::filesystem::exists(pathOf("run/cycles")));
}

TEST_F(EmptyingTest, RefusesAMissingOutputDirectory) {
  EmptyingParams params = smallBin("", 2, 1);
  EXPECT_THROW(emptyBin(simulation::makePart("l_bracket"), params), core::Error);
}

}  // namespace
}  // namespace binpick::emptying
