// Fuzz target for calib.yaml, the rig calibration in OpenCV FileStorage YAML: the input is the
// file, read by readRigCalibration and readRigCalibrationQuality. Both must refuse a bad file
// with a core::Error naming it (never a cv::Exception, a crash or an allocation sized by a
// matrix header), and a rig they accept must hold what validate() requires. Built with libFuzzer
// (fuzz/run-libfuzzer.sh rig_calibration) and with the seeded driver (random_input_driver.cpp,
// test rig_calibration_fuzz_smoke).
#include "binpick/io/rig_calibration.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace binpick;
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::string path = (fuzz::scratchDirectory() / "calib.yaml").string();
  fuzz::writeBytes(path, input);
  io::RigCalibration rig;
  if (fuzz::readsOrRefuses("readRigCalibration", path, input, [&] { rig = io::readRigCalibration(path); })) {
    try {
      rig.validate();
    } catch (const core::Error& error) {
      fuzz::reportFinding("readRigCalibration", std::string("accepted a rig that fails validate(): ") + error.what(),
                          input);
    }
  }
  fuzz::readsOrRefuses("readRigCalibrationQuality", path, input, [&] { io::readRigCalibrationQuality(path); });
  return 0;
}
