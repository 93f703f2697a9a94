// The named photometry presets.
#include "sensor/lighting_presets.hpp"

#include "binpick/core/error.hpp"

namespace binpick::simulation {
namespace {

// Dark, glossy parts in a bin whose walls and neighbours send back a third of the light: the
// exposure is raised for the dark parts, so highlights clip; the sensor is noisier, and the
// projector's wider aperture blurs the finest stripes on the parts above the focused floor.
PhotometryParams harsh() {
  PhotometryParams p;
  p.projector_white = 320.0;
  p.albedo_scale = 0.15;
  p.ambient = 12.0;
  p.global_light = 0.35;
  p.specular = 2.0;
  p.shininess = 200.0;
  p.read_noise = 3.0;
  p.defocus_per_dioptre = 12.0;
  return p;
}

}  // namespace

std::vector<std::string> photometryPresetNames() { return {"clean", "harsh"}; }

PhotometryParams photometryPreset(const std::string& name) {
  if (name == "clean") return PhotometryParams{};
  if (name == "harsh") return harsh();
  std::string known;
  for (const std::string& preset : photometryPresetNames()) known += (known.empty() ? "" : ", ") + preset;
  throw core::Error("unknown lighting preset '" + name + "' (known: " + known + ")");
}

}  // namespace binpick::simulation
