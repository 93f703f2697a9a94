#pragma once
// Named photometry presets of the virtual cell: the light a capture is rendered under, from the
// default bright matte parts ("clean") to dark glossy parts under strong indirect light ("harsh").
// A preset is a starting point: its PhotometryParams can be changed field by field (seed, bit
// depth, threads are left at their defaults). Stateless: thread-safe.
#include <string>
#include <vector>

#include "binpick/simulation/pattern_renderer.hpp"

namespace binpick::simulation {

// "clean": PhotometryParams{} (matte parts of albedo 0.55, 3% indirect light, 0.7 counts read
// noise). "harsh": dark glossy parts (albedo scaled by 0.15: parts 0.08, bin 0.045; specular 2.0,
// shininess 200: faces turned towards the rig clip), 35% indirect light, 3 counts read noise, twice the room
// light, a projector focused on the bin floor with twice the defocus (2-pixel stripes on the
// parts are nearly washed out) and set a little brighter for the dark parts. Throws core::Error
// naming an unknown preset and the known ones.
PhotometryParams photometryPreset(const std::string& name);

// The preset names photometryPreset knows, in a stable order.
std::vector<std::string> photometryPresetNames();

}  // namespace binpick::simulation
