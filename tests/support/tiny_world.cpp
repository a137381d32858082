#include "tiny_world.h"

namespace engine::test {

splat_lod::world::WorldOptions tiny_world_options(const std::filesystem::path& folder, std::uint64_t seed, int threads) {
    splat_lod::world::WorldOptions o;
    o.seed = seed;
    o.size_m = 96.0f;
    o.chunk_size_m = 32.0f;
    o.density = 0.1f;
    o.threads = threads;
    o.bake.refine_iterations = 3;
    o.bake.refine_cameras = 4;
    o.bake_width = 128;
    o.bake_height = 128;
    o.output = folder;
    return o;
}

}  // namespace engine::test
