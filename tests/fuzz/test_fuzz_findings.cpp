// What fuzzing the file readers found (fuzz/README.md, Findings), each kept as the smallest file
// that showed it: the reader must refuse it with a core::Error naming the file and what was
// wrong, before allocating anything sized by it.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "binpick/cell/cell_config.hpp"
#include "binpick/estimation/config.hpp"
#include "binpick/io/capture.hpp"
#include "binpick/io/rig_calibration.hpp"
#include "temp_directory_test.hpp"
#include "thrown_message.hpp"

namespace binpick::test {
namespace {

class FuzzFinding : public TempDirectoryTest {
 protected:
  std::string write(const std::string& name, const std::string& text) const {
    const std::string path = pathOf(name);
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
};

constexpr const char* kRecipe = "source: {replay: {path: captures}}\nrecipes: [{name: part, model: part.ply";

// OpenCV allocates a matrix from its header's rows and cols before it reads the data.
TEST_F(FuzzFinding, CalibrationMatrixHeaderIsCheckedBeforeOpenCvAllocatesIt) {
  const std::string path = write("calib.yaml",
                                 "%YAML:1.0\n---\ncamera_width: 640\ncamera_height: 480\n"
                                 "camera_matrix: !!opencv-matrix\n   rows: 100000\n   cols: 100000\n   dt: d\n"
                                 "   data: [ 1., 0., 2. ]\n");
  EXPECT_TRUE(throwsNaming([&] { io::readRigCalibration(path); },
                           path + ": 'camera_matrix' must be at most 16x16 (got 100000x100000)"));
  const std::string nd = write("nd.yaml",
                               "%YAML:1.0\n---\ncamera_width: 640\ncamera_height: 480\n"
                               "camera_matrix: !!opencv-nd-matrix\n   sizes: [ 100000, 100000, 100 ]\n   dt: d\n"
                               "   data: [ 1. ]\n");
  EXPECT_TRUE(throwsNaming([&] { io::readRigCalibration(nd); }, nd + ": 'camera_matrix' is not an OpenCV matrix"));
}

// OpenCV's FileStorage parser looped forever on this; yaml-cpp's LoadAll allocated without end on
// the second. Neither reaches a parser that misbehaves.
TEST_F(FuzzFinding, CalibrationFilesThatHangParsersAreRefused) {
  const std::string hang = write("hang.yaml", "%YAML:1.0\n   data:0\n---\n- 1\n");
  EXPECT_TRUE(throwsNaming([&] { io::readRigCalibration(hang); },
                           hang + ": not an OpenCV FileStorage YAML file (more than one YAML document)"));
  const std::string comma = write("comma.yaml", "%YAML:1.0\n---\n- 1\n, 3]\n");
  EXPECT_TRUE(throwsNaming([&] { io::readRigCalibrationQuality(comma); }, comma + ": not an OpenCV FileStorage YAML"));
  const std::string deep = write("deep.yaml", "a: {b: {c: {d: {e: 1}}}}\n");
  EXPECT_TRUE(throwsNaming([&] { io::readRigCalibration(deep); }, deep + ": not an OpenCV FileStorage YAML file (nested"));
}

// The estimation settings named a wrong method without naming the file.
TEST_F(FuzzFinding, UnknownDetectionMethodNamesTheFile) {
  const std::string path = write("detection.yaml", "detection: {method: foo}\n");
  EXPECT_TRUE(throwsNaming([&] { estimation::loadEstimationConfig(path); },
                           path + ": detection.method detector params: method 'foo' is unknown"));
}

// yaml-cpp keys may be lists or mappings; converting one to a name threw a YAML exception.
TEST_F(FuzzFinding, SettingsKeyThatIsNotANameIsRefused) {
  const std::string top = write("top.yaml", std::string(kRecipe) + "}]\n[a, b]: 1\n");
  EXPECT_TRUE(throwsNaming([&] { cell::loadCellConfig(top); },
                           top + ": the top level has a key that is not a name"));
  const std::string nested = write("nested.yaml", std::string(kRecipe) + "}]\nlimits: {? {x: 1} : 2}\n");
  EXPECT_TRUE(throwsNaming([&] { cell::loadCellConfig(nested); }, nested + ": limits has a key that is not a name"));
}

// Every fold of a symmetry is a rotation kept and tried with every grasp.
TEST_F(FuzzFinding, SymmetryOrderIsBounded) {
  const std::string path = write("cell.yaml", std::string(kRecipe) + ", symmetry: {order: 2000000000}}]\n");
  EXPECT_TRUE(throwsNaming([&] { cell::loadCellConfig(path); },
                           path + ": recipes[0].symmetry.order must be in [1, 360] (got 2000000000)"));
}

// A settings file naming a device as its grasps file was read until memory ran out.
TEST_F(FuzzFinding, GraspsFileMustBeARegularFile) {
  const std::string path = write("cell.yaml", std::string(kRecipe) + ", grasps: /dev/zero}]\n");
  EXPECT_TRUE(throwsNaming([&] { cell::loadCellConfig(path); },
                           "recipes[0].grasps: /dev/zero: cannot open the configuration file (not a regular file)"));
}

}  // namespace
}  // namespace binpick::test
