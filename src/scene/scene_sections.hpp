// The scene parser's sections, one file each (domain, grid, solver and time; materials; bodies;
// blocks with their contact and coupling; FEM bodies; SPH; output, limits and view). Each reads
// its part of the tree into the Scene, failing with the file, line, key and a valid value.
// Internal to the scene library.
#pragma once

#include <map>
#include <sstream>
#include <string>

#include "mpm_sdem/scene/scene.hpp"
#include "yaml_reader.hpp"

namespace mpm_sdem::scene {

inline constexpr Real kDeg = M_PI / 180;

// A number as the messages show it.
inline std::string num(Real v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// world_section.cpp
void parseDomain(const Context& ctx, const MapReader& top, Scene& s);
void parseGrid(const Context& ctx, const MapReader& top, Scene& s);
void parseSolver(const Context& ctx, const MapReader& top, Scene& s);
void parseTime(const Context& ctx, const MapReader& top, Scene& s);
// material_section.cpp: the list of materials; their indices by name.
std::map<std::string, int> parseMaterials(const Context& ctx, const MapReader& top, Scene& s);
// body_section.cpp
ShapeDef parseShape(const Context& ctx, const MapReader& r);
void parseBodies(const Context& ctx, const MapReader& top, Scene& s,
                 const std::map<std::string, int>& materials);
// block_section.cpp: blocks, block_contact and coupling.
void parseBlocks(const Context& ctx, const MapReader& top, Scene& s);
// fem_section.cpp
void parseFemBodies(const Context& ctx, const MapReader& top, Scene& s);
// sph_section.cpp
void parseSph(const Context& ctx, const MapReader& top, Scene& s);
// output_section.cpp: output, limits and view.
void parseOutput(const Context& ctx, const MapReader& top, Scene& s);
void parseLimits(const Context& ctx, const MapReader& top, Scene& s);
void parseView(const Context& ctx, const MapReader& top, Scene& s);

}  // namespace mpm_sdem::scene
