// What a cycle directory holds, and which cycle directories the store keeps.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "artefact_test_data.hpp"
#include "binpick/cell/artefact_store.hpp"
#include "binpick/io/geometry_io.hpp"
#include "binpick/io/image_file.hpp"
#include "temp_directory_test.hpp"
#include "thrown_message.hpp"

namespace binpick::test {
namespace {

namespace fs = std::filesystem;
using cell::ArtefactParams;
using cell::ArtefactStore;
using cell::CycleArtefacts;

std::string fileText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

class ArtefactsStore : public TempDirectoryTest {
 protected:
  ArtefactParams paramsIn(const std::string& name) const {
    ArtefactParams params;
    params.directory = pathOf(name);
    return params;
  }
  // A cycle with only its detections text, `bytes` long.
  static CycleArtefacts textCycle(uint64_t cycle, std::size_t bytes = 10) {
    CycleArtefacts artefacts;
    artefacts.cycle = cycle;
    artefacts.detections_json = std::string(bytes, 'd');
    return artefacts;
  }
  static std::vector<std::string> cycleNumbers(const ArtefactStore& store) {
    std::vector<std::string> numbers;
    for (const std::string& path : store.cycles()) numbers.push_back(cycleNumberOf(path));
    return numbers;
  }
};

TEST_F(ArtefactsStore, SavesEveryArtefactOfACycle) {
  ArtefactStore store(paramsIn("cycles"));
  const io::Capture capture = tinyCapture();
  const io::PointCloud cloud = tinyCloud();
  const cv::Mat overlay(6, 8, CV_8UC3, cv::Scalar(0, 255, 0));
  CycleArtefacts cycle;
  cycle.cycle = 42;
  cycle.capture = &capture;
  cycle.cloud = &cloud;
  cycle.detections_json = "{\"parts\": []}\n";
  cycle.overlay = &overlay;

  const std::string directory = store.save(cycle);
  EXPECT_TRUE(isCycleName(nameOf(directory))) << directory;
  EXPECT_EQ(cycleNumberOf(directory), "000042");
  EXPECT_EQ(fs::path(directory).parent_path(), fs::path(pathOf("cycles")));
  EXPECT_EQ(entriesOf(directory), (std::set<std::string>{"capture", "cloud.ply", "detections.json", "overlay.png"}));
  EXPECT_EQ(io::readCapture(directory + "/capture").images.size(), 2u);
  EXPECT_EQ(io::readPointCloud(directory + "/cloud.ply").size(), 3u);
  EXPECT_EQ(fileText(directory + "/detections.json"), cycle.detections_json);
  const cv::Mat overlay_read = io::readImageFile(directory + "/overlay.png");
  EXPECT_EQ(cv::norm(overlay_read, overlay, cv::NORM_INF), 0.0);
  EXPECT_EQ(store.cycles(), std::vector<std::string>{directory});
}

TEST_F(ArtefactsStore, SavesOnlyWhatIsEnabledAndProvided) {
  ArtefactParams params = paramsIn("cycles");
  params.capture = false;
  params.overlay = false;
  ArtefactStore store(params);
  const io::Capture capture = tinyCapture();
  const cv::Mat overlay(6, 8, CV_8UC3);
  CycleArtefacts cycle = textCycle(7);
  cycle.capture = &capture;
  cycle.overlay = &overlay;  // no cloud given
  EXPECT_EQ(entriesOf(store.save(cycle)), std::set<std::string>{"detections.json"});
}

TEST_F(ArtefactsStore, SkipsEmptyArtefactsButKeepsTheCycle) {
  ArtefactStore store(paramsIn("cycles"));
  const io::Capture no_images;
  const io::PointCloud no_points;
  const cv::Mat no_overlay;
  CycleArtefacts cycle;
  cycle.cycle = 5;
  cycle.capture = &no_images;
  cycle.cloud = &no_points;
  cycle.overlay = &no_overlay;
  const std::string directory = store.save(cycle);
  EXPECT_TRUE(entriesOf(directory).empty());
  EXPECT_EQ(store.cycles(), std::vector<std::string>{directory});
}

TEST_F(ArtefactsStore, KeepsOnlyTheNewestCycles) {
  ArtefactParams params = paramsIn("cycles");
  params.max_cycles = 3;
  ArtefactStore store(params);
  for (uint64_t cycle = 1; cycle <= 5; ++cycle) store.save(textCycle(cycle));
  EXPECT_EQ(cycleNumbers(store), (std::vector<std::string>{"000003", "000004", "000005"}));
  EXPECT_EQ(entriesOf(pathOf("cycles")).size(), 3u);
}

TEST_F(ArtefactsStore, KeepsTheNewestCyclesThatFitTheSizeBound) {
  ArtefactParams params = paramsIn("cycles");
  params.max_bytes = 2500;  // two cycles of 1000 bytes fit, three do not
  ArtefactStore store(params);
  for (uint64_t cycle = 1; cycle <= 4; ++cycle) store.save(textCycle(cycle, 1000));
  EXPECT_EQ(cycleNumbers(store), (std::vector<std::string>{"000003", "000004"}));
}

TEST_F(ArtefactsStore, KeepsTheNewestCycleEvenWhenItAloneIsTooLarge) {
  ArtefactParams params = paramsIn("cycles");
  params.max_bytes = 100;
  ArtefactStore store(params);
  store.save(textCycle(1, 50));
  const std::string newest = store.save(textCycle(2, 1000));
  EXPECT_EQ(store.cycles(), std::vector<std::string>{newest});
}

TEST_F(ArtefactsStore, RepeatedCycleNumbersGetDistinctDirectories) {
  ArtefactStore store(paramsIn("cycles"));
  const std::string first = store.save(textCycle(1));
  const std::string second = store.save(textCycle(1));  // e.g. after a restart, same second
  EXPECT_NE(first, second);
  EXPECT_TRUE(isCycleName(nameOf(second))) << second;
  EXPECT_EQ(store.cycles(), (std::vector<std::string>{first, second}));
}

TEST_F(ArtefactsStore, RotationLeavesForeignFilesAndDirectoriesAlone) {
  const fs::path directory = pathOf("cycles");
  fs::create_directories(directory / "my notes");
  fs::create_directories(directory / "cycle-000001");               // no timestamp
  fs::create_directories(directory / "cycle-12-20260101T000000Z");  // too few digits
  fs::create_directories(directory / ".partial-something");         // not a cycle's
  std::ofstream(directory / "cycle-000002-20200101T000000Z") << "a file, not a directory";
  std::ofstream(directory / "README.txt") << "kept";
  fs::create_directories(pathOf("elsewhere"));
  fs::create_directory_symlink(pathOf("elsewhere"), directory / "cycle-000003-20200101T000000Z");
  const std::set<std::string> foreign = entriesOf(directory.string());

  ArtefactParams params = paramsIn("cycles");
  params.max_cycles = 1;
  params.max_bytes = 1;
  ArtefactStore store(params);
  std::string newest;
  for (uint64_t cycle = 1; cycle <= 3; ++cycle) newest = store.save(textCycle(cycle));

  std::set<std::string> expected = foreign;
  expected.insert(nameOf(newest));
  EXPECT_EQ(entriesOf(directory.string()), expected);
  EXPECT_TRUE(fs::exists(pathOf("elsewhere")));
  EXPECT_EQ(store.cycles(), std::vector<std::string>{newest});
}

TEST_F(ArtefactsStore, RemovesLeftoversOfAnInterruptedSave) {
  const fs::path directory = pathOf("cycles");
  const fs::path leftover = directory / ".partial-cycle-000009-20260101T000000Z";
  fs::create_directories(leftover / "capture");
  std::ofstream(leftover / "cloud.ply") << "half written";
  fs::create_directories(directory / ".partial-mine");

  const ArtefactStore store(paramsIn("cycles"));
  EXPECT_FALSE(fs::exists(leftover));
  EXPECT_TRUE(fs::exists(directory / ".partial-mine"));
  EXPECT_TRUE(store.cycles().empty());
}

TEST_F(ArtefactsStore, CreatesItsDirectory) {
  const ArtefactStore store(paramsIn("a/b/c"));
  EXPECT_TRUE(fs::is_directory(pathOf("a/b/c")));
}

TEST_F(ArtefactsStore, ParamsNameTheBadField) {
  ArtefactParams params = paramsIn("cycles");
  params.max_cycles = 0;
  EXPECT_TRUE(throwsNaming([&] { params.validate(); }, "artefacts.max_cycles"));
  params = paramsIn("cycles");
  params.max_bytes = 0;
  EXPECT_TRUE(throwsNaming([&] { ArtefactStore store(params); }, "artefacts.max_bytes"));
  params = paramsIn("cycles");
  params.directory.clear();
  EXPECT_TRUE(throwsNaming([&] { params.validate(); }, "artefacts.directory"));
  params = paramsIn("cycles");
  params.threads = -1;
  EXPECT_TRUE(throwsNaming([&] { params.validate(); }, "artefacts.threads"));
  EXPECT_EQ(thrownMessage([&] { paramsIn("cycles").validate(); }), "");
}

}  // namespace
}  // namespace binpick::test
