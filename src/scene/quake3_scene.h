#pragma once
// A Quake 3 map as a textured scene (thesis 3.3.2: the maps vtgeo retextured), read directly from
// the game's .pk3 archives.
//
// Drawn: polygon and mesh surfaces, one face per connected piece (the map compiler gathers
// triangles of one plane or shader from many brushes into one surface), and patches tessellated
// at `patchLevel` (bezier_patch.h), one face each.
// Skipped and counted (SkippedFaces): flares and billboards, sky, nodraw and fog shaders, unknown
// surface types, surfaces with a non-finite vertex, and surfaces without a triangle of non-zero
// area. Every source image a drawn face uses is extracted from its archive into `imageFolder`
// under its entry name; a texture without an image gets the checker image and a warning.
// Positions go through quake_axes.h; triangles are wound counter-clockwise about the surface's
// vertex normals. The viewpoints are the info_player_deathmatch spawn points (else the first
// present of info_player_start and the CTF team spawns) at view height, looking along their angle.

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

#include "scene/bezier_patch.h"
#include "scene/bsp_file.h"
#include "scene/package_files.h"
#include "scene/textured_scene.h"

namespace vt {

struct Quake3Options {
  int patchLevel = kPatchTessellationLevel;
};

// `map` is a map name ("q3dm6ish") or an entry ("maps/q3dm6ish.bsp").
// The scene's name for `map`: its entry's name without folder and extension, as the packages
// spell it (InputError when there is no such map).
std::string quake3MapName(const PackageFiles& files, std::string_view map);

TexturedScene loadQuake3Map(const PackageFiles& files, std::string_view map,
                            const std::filesystem::path& imageFolder,
                            const Quake3Options& options = {});

// The texture of a drawn surface's shader (its number in the map and its name): an index into
// `scene.textures`, which the function fills. loadQuake3Map finds the images in the packages.
using ShaderTextures =
    std::function<uint32_t(int32_t shader, const std::string& name, TexturedScene& scene)>;

// The faces, skipped surfaces and viewpoints of a parsed map, `source` naming it in errors.
// Refuses, before tessellating, drawn surfaces that would give more than kMaxMapVertices vertices
// or kMaxMapIndices indices (common/resource_limits.h). The scene's name is left empty.
TexturedScene quake3Scene(const BspFile& bsp, const std::string& source,
                          const ShaderTextures& textureFor, const Quake3Options& options = {});

}  // namespace vt
