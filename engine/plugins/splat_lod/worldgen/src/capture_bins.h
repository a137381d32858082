#pragma once
// Internal to the world import (world_import.h): the capture's Gaussians binned by chunk into files
// on disk (bounded memory whatever the capture's size), and the far layer kept in memory up to a cap.
#include <cstdint>
#include <filesystem>
#include <map>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "splat_lod/core/splat_cloud.h"

namespace splat_lod::world {

// One Gaussian of `from` appended to `to` (the same SH degree; extras and LOD attributes are not kept).
void append_gaussian(SplatCloud& to, const SplatCloud& from, std::size_t i);

class ChunkBins {
public:
    // Bin files go into `folder` (created); buffers are written out once they hold `flush_bytes`.
    ChunkBins(std::filesystem::path folder, int sh_degree, std::uint64_t flush_bytes);
    void add(const glm::ivec2& cell, const SplatCloud& cloud, std::size_t i);
    void flush();
    // The cells that hold a Gaussian, in grid order (rows of increasing z, each of increasing x).
    std::vector<glm::ivec2> cells() const;
    std::uint64_t count(const glm::ivec2& cell) const;
    std::uint64_t largest() const;  // the most Gaussians in one cell
    std::uint64_t flushes() const { return flushes_; }
    // The cell's Gaussians in the order they were added (call flush() first); throws engine::Error
    // naming the bin file when it cannot be read back whole.
    SplatCloud read(const glm::ivec2& cell) const;
    void remove(const glm::ivec2& cell) const;  // its file, once baked

private:
    std::filesystem::path file(const glm::ivec2& cell) const;
    std::size_t floats_per_gaussian() const;

    std::filesystem::path folder_;
    int sh_degree_ = 0;
    std::uint64_t flush_bytes_ = 0, buffered_bytes_ = 0, flushes_ = 0;
    std::map<std::pair<int, int>, std::vector<float>> buffers_;  // (z, x): grid order
    std::map<std::pair<int, int>, std::uint64_t> counts_;
};

// Gaussians kept out of the chunks (huge or outside the world box): at most `cap`, the ones with the
// largest score when there are more.
class FarLayer {
public:
    FarLayer(int sh_degree, std::uint64_t cap);
    void add(const SplatCloud& cloud, std::size_t i, float score);
    SplatCloud finish();  // in the order added, after dropping the lowest scores
    std::uint64_t dropped() const { return dropped_; }

private:
    void compact(std::uint64_t keep);

    SplatCloud cloud_;
    std::vector<float> scores_;
    std::uint64_t cap_ = 0, dropped_ = 0;
};

}  // namespace splat_lod::world
