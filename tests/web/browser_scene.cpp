// For the browser test: writes binpickd settings replaying the virtual cell's test bin (rendered
// once per build tree, tests/cell/service/cell_scene.hpp) with the web view on a free port and
// each cycle's overlay saved, to DIR/binpickd.yaml.
//   web_browser_scene DIR
#include <fstream>
#include <iostream>

#include "../cell/service/cell_scene.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: web_browser_scene DIR\n";
    return 2;
  }
  const std::string directory = argv[1];
  using namespace binpick::cell::testing;
  const std::string extra =
      "web: {bind_address: 127.0.0.1, port: 0}\n"
      "artefacts: {directory: " +
      directory + "/cycles, capture: false, cloud: false}\n";
  std::ofstream(directory + "/binpickd.yaml") << cellConfigYaml(cellScene(), extra);
  std::cout << directory << "/binpickd.yaml\n";
  return 0;
}
