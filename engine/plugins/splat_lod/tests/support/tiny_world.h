#pragma once
// The tests' tiny generated world: 3 × 3 chunks of 32 m at density 0.1 (about 15,000 Gaussians),
// 128 × 128 bake cameras and a 3-iteration refinement; a second or so to generate. And helpers to
// compare worlds on disk.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

#include "splat_lod/worldgen/world_generator.h"

namespace engine::test {

splat_lod::world::WorldOptions tiny_world_options(const std::filesystem::path& folder, std::uint64_t seed = 11,
                                                  int threads = 2);

// The tiny world in output_root()/sample_game/<name>, generated on first use and reused after (the
// generator keeps a world made with the same options); each name is one suite's own copy.
std::filesystem::path cached_tiny_world(const std::string& name);

// Every file below `folder` by relative path (generic form), with its bytes.
std::map<std::string, std::string> folder_bytes(const std::filesystem::path& folder);

// The files of a world with the generation folder taken out of their paths ("gen-2/chunks/x" →
// "chunks/x", and so in world.json): what regenerating the same world into the same folder keeps.
std::map<std::string, std::string> without_generation(const std::map<std::string, std::string>& files);

}  // namespace engine::test
