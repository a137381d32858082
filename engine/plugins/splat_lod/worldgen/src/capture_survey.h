#pragma once
// Internal to the world import (world_import.h): the survey pass over a capture (a strided sample of
// its centres, the mean normal of its flat Gaussians) and the world frame and chunk grid chosen from it.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "splat_lod/core/capture_source.h"
#include "splat_lod/worldgen/world_import.h"

namespace splat_lod::world {

struct CaptureSample {
    std::vector<glm::vec3> positions;  // every stride-th kept Gaussian's centre, capture frame
    std::uint64_t stride = 1;
    glm::dmat3 normal_moments{0.0};  // Σ n·nᵀ over flat, opaque Gaussians
    std::uint64_t flat = 0;
    std::uint64_t read = 0, dropped_by_reader = 0, invisible = 0;
    int sh_degree = 0;
    double median_extent = 0.0;  // of the sampled Gaussians
};

// Reads every part once. `sample_max` bounds the sample (it holds between sample_max and 2·sample_max
// centres once the capture is larger). Progress as stage "survey".
CaptureSample survey_capture(const Capture& capture, std::uint64_t sample_max,
                             const std::function<void(std::uint64_t parts_done)>& progress);

struct CaptureFrame {
    glm::dvec3 up{0.0, 1.0, 0.0};  // capture frame
    std::string up_source;
    glm::dmat3 rotation{1.0};  // capture → world
    glm::dvec3 translation{0.0};
    float chunk_size = 64.0f;
    int chunks_per_side = 1;                   // even, so that cells run from −count/2
    float height_lo = 0.0f, height_hi = 0.0f;  // world frame: the kept heights
    float degenerate_extent = 0.0f;            // below it a Gaussian is degenerate
    float footprint = 0.0f;                    // the 1–99 % square's side
    float height_span = 0.0f;                  // the 1–99 % span of the heights
    float huge_extent = 0.0f;                  // above it a Gaussian goes to the far layer
    bool aerial = false;
    // The quadtree of chunks (ChunkEntry::span): per grid cell (cell_index order), the span of the chunk
    // that holds it. Four sibling chunks whose sample estimates sum to at most the densest cell's are one chunk.
    std::vector<std::uint8_t> spans;
    float size() const { return chunk_size * static_cast<float>(chunks_per_side); }
    // The chunk holding grid `cell`: its lowest cell, and its span in `span`.
    glm::ivec2 chunk_of(const glm::ivec2& cell, int& span) const;
    float scale() const { return chunk_size / 64.0f; }
    // The chunk cell of a world-frame centre, or false outside the world box.
    bool cell_of(const glm::vec3& p, glm::ivec2& cell) const;
};

// Throws engine::Error naming `capture_name` when the sample is empty or has no horizontal extent.
CaptureFrame choose_frame(const CaptureSample& sample, const ImportOptions& options, const std::string& capture_name);

}  // namespace splat_lod::world
