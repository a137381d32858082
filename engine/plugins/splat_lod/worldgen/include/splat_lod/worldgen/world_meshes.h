#pragma once
// Internal to the world generator: the glTF props the world places (a house with a gabled roof, a
// fence segment, a waymark post) and a coarse terrain mesh under the splats, written as binary
// glTF (.glb) through tinygltf, with flat-shaded faces and base colour factors (no textures), so
// the engine's loader (engine/assets/mesh_asset.h) draws them with its mesh pass.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "splat_lod/synth/world_terrain.h"

namespace splat_lod::world {

// Writes kHouseMesh, kFenceMesh and kPostMesh (world_layout.h) below `folder`, atomically.
// Returns the bytes written.
std::uint64_t write_prop_meshes(const std::filesystem::path& folder);

// Writes kTerrainMesh: a grid over the whole world at a spacing of size / 128 (at least 4 m), each
// vertex 10 cm below the lowest ground around it, so that the ground Gaussians win the depth test
// where they cover the ground and the mesh only fills the gaps between them. Returns the bytes written.
std::uint64_t write_terrain_mesh(const std::filesystem::path& folder, const WorldTerrain& terrain);

}  // namespace splat_lod::world
