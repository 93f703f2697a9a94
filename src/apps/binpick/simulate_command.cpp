// binpick simulate --part NAME [--objects N] [--seed S] --out DIR   (depth-camera cloud of a pile)
// binpick simulate --list-parts
// binpick simulate --export-part NAME FILE
// Writes DIR/scene.ply (organized cloud, camera frame, metres), DIR/model.ply (the part mesh) and
// DIR/truth.json (T_camera_object and visibility of every object).
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "arguments.hpp"
#include "binpick/io/error.hpp"
#include "binpick/io/geometry_io.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/pile.hpp"
#include "commands.hpp"

namespace binpick::cli {
namespace {

nlohmann::json truthJson(const sim::PileScene& scene, const sim::Part& part) {
  nlohmann::json objects = nlohmann::json::array();
  for (const sim::ObjectTruth& o : scene.objects) {
    nlohmann::json rows = nlohmann::json::array();
    for (int r = 0; r < 4; ++r) {
      const auto m = o.T_camera_object.matrix();
      rows.push_back({m(r, 0), m(r, 1), m(r, 2), m(r, 3)});
    }
    objects.push_back({{"pose", rows}, {"visible_fraction", o.visible_fraction}, {"visible_pixels", o.visible_pixels}});
  }
  return {{"part", part.name}, {"units", "m"}, {"objects", objects}};
}

int listParts() {
  for (const std::string& name : sim::partNames()) std::cout << name << "  " << sim::makePart(name).description << "\n";
  return 0;
}

}  // namespace

int runSimulate(const std::vector<std::string>& raw) {
  if (!raw.empty() && raw[0] == "--list-parts") return listParts();
  if (raw.size() == 3 && raw[0] == "--export-part") {
    writeMesh(raw[2], sim::makePart(raw[1]).mesh);
    return 0;
  }
  const Arguments args(raw, {"--part", "--objects", "--seed", "--out"}, {});
  const sim::Part part = sim::makePart(args.required("--part"));
  sim::PileParams params;
  params.objects = args.integer("--objects").value_or(params.objects);
  params.seed = static_cast<uint64_t>(args.integer("--seed").value_or(1));
  params.validate();
  const std::filesystem::path out = args.required("--out");
  std::filesystem::create_directories(out);
  const sim::PileScene scene = sim::generatePile(part.mesh, params);
  writePointCloud((out / "scene.ply").string(), scene.cloud);
  writeMesh((out / "model.ply").string(), part.mesh);
  std::ofstream truth(out / "truth.json");
  truth << truthJson(scene, part).dump(2) << "\n";
  if (!truth) throw Error((out / "truth.json").string() + ": cannot write");
  std::cerr << "simulated " << params.objects << " x " << part.name << " into " << out.string() << "\n";
  return 0;
}

}  // namespace binpick::cli
