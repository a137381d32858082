// The quadtree over the chunk grid (splat_lod/core/chunk_quadtree.h).
#include "splat_lod/core/chunk_quadtree.h"

#include <cmath>
#include <cstdio>

namespace splat_lod::world {
namespace {

int floor_div(int a, int b) {
    const int q = a / b;
    return (a % b != 0 && (a < 0) != (b < 0)) ? q - 1 : q;
}

}  // namespace

int group_depths(int chunks_per_side) {
    int depths = 0;
    while ((1 << depths) < chunks_per_side) ++depths;
    return depths;
}

int chunks_per_side(const WorldManifest& m) {
    return static_cast<int>(std::lround(m.size_m / m.chunk_size_m));
}

glm::ivec2 group_of_chunk(const glm::ivec2& chunk_cell, int count, int depth) {
    const glm::ivec2 i = chunk_cell + glm::ivec2(count / 2);
    return {floor_div(i.x, 1 << depth), floor_div(i.y, 1 << depth)};
}

std::string group_id(int depth, const glm::ivec2& index) {
    char text[48];
    std::snprintf(text, sizeof text, "group_%d_%+04d_%+04d", depth, index.x, index.y);
    return text;
}

}  // namespace splat_lod::world
