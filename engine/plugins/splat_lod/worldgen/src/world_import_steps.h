#pragma once
// Internal to the world import (world_import.h): the steps a whole import, a shard of one and their merge
// share, so that all make the same bytes: the capture opened with its fingerprint, the survey, the
// binning (of every chunk or of a shard's), the bakes into a folder, the manifest without its chunks.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "capture_bins.h"
#include "capture_survey.h"
#include "splat_lod/core/capture_source.h"
#include "splat_lod/core/world_manifest.h"
#include "splat_lod/worldgen/world_import.h"
#include "world_build.h"

namespace splat_lod::world {

// What every run of an import finds first.
struct ImportPlan {
    Capture capture;
    std::string fingerprint;  // of the capture's files, the options and the import's version
    CaptureSample sample;     // after survey_import()
    CaptureFrame frame;
    std::vector<eval::CameraPose> training;  // options.cameras in the world frame (after survey_import())
};

// Checks the options, opens the capture and takes its fingerprint (no survey yet).
ImportPlan open_import(const ImportOptions& options, ImportSummary& summary);

// The world in options.output when it is this import (same fingerprint, every file of its size).
std::optional<WorldManifest> cached_import(const ImportOptions& options, const std::string& fingerprint);

// The result of an import that finds its work done: `m` as it is in `folder`, summarised.
ImportResult cached_import_result(WorldManifest m, const std::filesystem::path& folder, Clock::time_point start);

// Reads the capture once for the sample, chooses the frame and reads the training cameras into it
// (plan.sample, plan.frame, plan.training).
void survey_import(const ImportOptions& options, ImportPlan& plan, ImportSummary& summary, Clock::time_point start);

// Which chunk cells a run bakes: every cell, or a shard's (empty function: every cell).
using CellFilter = std::function<bool(const glm::ivec2& cell)>;

// The world's options for the chunk bakes and groups at the frame's scale, writing below `root`, with as
// many bakes at once as the memory cap allows for chunks of up to `largest_chunk` Gaussians.
WorldOptions import_world_options(const ImportOptions& options, const CaptureFrame& frame, std::uint64_t largest_chunk,
                                  const std::filesystem::path& root);

// The ground under each chunk, from the survey's sample.
GroundGrid ground_grid(const CaptureSample& sample, const CaptureFrame& frame);

// The manifest without chunks, props or groups: sizes, the generator (with the fingerprint), stream
// levels, ground grid and the capture's frame.
WorldManifest import_manifest(const ImportOptions& options, const WorldOptions& w, const ImportPlan& plan,
                              const GroundGrid& ground);

// What a whole import and a shard both make below `root`: the capture binned into `bins_folder` (only the
// cells `keep` accepts; an empty `keep` is a whole import, which fails when no cell holds a Gaussian),
// every bin baked into root / generation and the bins removed; then the manifest without groups: the far
// layer (when `far_layer`) and the chunks' entries. `w` gets the world's options the bakes used.
WorldManifest bake_capture(const ImportOptions& options, const ImportPlan& plan, const std::filesystem::path& root,
                           const std::filesystem::path& generation, const std::filesystem::path& bins_folder,
                           const CellFilter& keep, bool far_layer, WorldOptions& w, ImportSummary& summary,
                           Clock::time_point start);

// The grid-order index of a chunk cell: rows of increasing z, each of increasing x.
std::size_t cell_index(const CaptureFrame& frame, const glm::ivec2& cell);

}  // namespace splat_lod::world
