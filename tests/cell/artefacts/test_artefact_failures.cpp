// A store that cannot write says where, and leaves neither a partial nor a half cycle behind.
// (The tests run as root, so permissions cannot make a write fail: a regular file stands where a
// directory is needed, or an artefact is one the writers refuse.)
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "artefact_test_data.hpp"
#include "binpick/cell/artefact_store.hpp"
#include "temp_directory_test.hpp"
#include "thrown_message.hpp"

namespace binpick::test {
namespace {

namespace fs = std::filesystem;
using cell::ArtefactParams;
using cell::ArtefactStore;
using cell::CycleArtefacts;

class ArtefactsFailures : public TempDirectoryTest {
 protected:
  ArtefactParams paramsIn(const std::string& directory) const {
    ArtefactParams params;
    params.directory = directory;
    return params;
  }
};

TEST_F(ArtefactsFailures, DirectoryBelowARegularFileIsAnErrorNamingIt) {
  std::ofstream(pathOf("plain-file")) << "not a directory";
  const std::string directory = pathOf("plain-file/cycles");
  EXPECT_TRUE(throwsNaming([&] { ArtefactStore store(paramsIn(directory)); }, directory));
  EXPECT_TRUE(throwsNaming([&] { ArtefactStore store(paramsIn(pathOf("plain-file"))); }, pathOf("plain-file")));
}

TEST_F(ArtefactsFailures, DirectoryReplacedByAFileFailsTheSaveNamingTheCycle) {
  const std::string directory = pathOf("cycles");
  ArtefactStore store(paramsIn(directory));
  fs::remove(directory);
  std::ofstream(directory) << "replaced";
  CycleArtefacts cycle;
  cycle.cycle = 3;
  cycle.detections_json = "{}";
  const std::string message = thrownMessage([&] { store.save(cycle); });
  EXPECT_NE(message.find(directory + "/cycle-000003-"), std::string::npos) << message;
  EXPECT_TRUE(fs::is_regular_file(directory));
}

TEST_F(ArtefactsFailures, AFailingArtefactLeavesNoPartialDirectory) {
  const std::string directory = pathOf("cycles");
  ArtefactStore store(paramsIn(directory));
  const io::Capture capture = tinyCapture();  // written before the cloud fails
  io::PointCloud nan_cloud = tinyCloud();     // the PLY writer refuses NaN in an unorganized cloud
  nan_cloud.points[1].x() = std::nanf("");
  CycleArtefacts cycle;
  cycle.cycle = 8;
  cycle.capture = &capture;
  cycle.cloud = &nan_cloud;
  cycle.detections_json = "{}";

  const std::string message = thrownMessage([&] { store.save(cycle); });
  EXPECT_NE(message.find("cannot save cycle 8 to " + directory + "/cycle-000008-"), std::string::npos) << message;
  EXPECT_NE(message.find("cloud.ply"), std::string::npos) << message;  // and what failed
  EXPECT_TRUE(entriesOf(directory).empty());
  EXPECT_TRUE(store.cycles().empty());

  // The store stays usable.
  cycle.cloud = nullptr;
  const std::string saved = store.save(cycle);
  EXPECT_EQ(entriesOf(directory), std::set<std::string>{nameOf(saved)});
}

TEST_F(ArtefactsFailures, AnUnwritableOverlayLeavesNoPartialDirectory) {
  const std::string directory = pathOf("cycles");
  ArtefactStore store(paramsIn(directory));
  const cv::Mat two_channels(6, 8, CV_8UC2, cv::Scalar(1, 2));  // PNG has no such format
  CycleArtefacts cycle;
  cycle.cycle = 9;
  cycle.detections_json = "{}";
  cycle.overlay = &two_channels;
  EXPECT_TRUE(throwsNaming([&] { store.save(cycle); }, "overlay.png"));
  EXPECT_FALSE(anyPartial(directory));
  EXPECT_TRUE(entriesOf(directory).empty());
}

}  // namespace
}  // namespace binpick::test
