#pragma once
// bench_paper's command line.
#include <cstdint>
#include <string>
#include <vector>

#include "bench_scenes.hpp"

namespace binpick::bench {

struct PaperBenchOptions {
  // The paper's six parts (Fig. 3): gear, L1, L2, magnet, switch, bulge.
  std::vector<std::string> parts{"gear", "l_bracket", "l_bracket_long", "ring_magnet", "switch", "bulge"};
  std::vector<std::string> methods{"binpick", "ppf5", "ppf1", "opencv_ppf", "pcl_ppf"};
  std::vector<CloudInput> inputs{CloudInput::Exact, CloudInput::Reconstructed};
  std::vector<std::string> sections{"paper", "selection", "scaling"};
  int scenes = 2;                       // per part; the paper: 50
  int peer_scenes = 1;                  // OpenCV's and PCL's matchers take minutes per scene: the first K only
  std::vector<std::string> peer_parts;  // and only these parts (empty: every part)
  int objects = 20;                     // per scene; the paper: 20
  uint64_t seed = 1;                    // scene s of every part has seed + s
  int threads = 0;                      // 0: all hardware threads
  std::string scaling_part = "l_bracket";
  int scaling_scenes = 2;
  std::string out = "docs/benchmark";
  std::string settings;                 // binpick's detector settings (a detection.yaml); empty: the defaults
  std::string reconstruction_settings;  // a file with a `reconstruction:` section; empty: the defaults
  bool explain = false;                 // --explain: binpick's detections one per line, right or wrong
  bool help = false;                    // --help: print paperBenchUsage() and run nothing
  bool has(const std::string& section) const;
  bool runsPeersOn(const std::string& part) const;
};

const char* paperBenchUsage();

// Throws core::Error naming the bad option or value.
PaperBenchOptions parsePaperBenchOptions(int argc, char** argv);

}  // namespace binpick::bench
