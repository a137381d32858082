#pragma once
// The tests' tiny generated world: 3 × 3 chunks of 32 m at density 0.1 (about 15,000 Gaussians),
// 128 × 128 bake cameras and a 3-iteration refinement; a second or so to generate.
#include <cstdint>
#include <filesystem>

#include "splat_lod/world/world_generator.h"

namespace engine::test {

splat_lod::world::WorldOptions tiny_world_options(const std::filesystem::path& folder, std::uint64_t seed = 11,
                                                  int threads = 2);

}  // namespace engine::test
