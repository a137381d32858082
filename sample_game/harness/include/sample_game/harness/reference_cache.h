#pragma once
// The cached reference of the profile (`sample_game_harness --reference`, reference_run.h): for a few path
// frames spread over every segment, the frame rendered supersampled in `baseline` mode with every
// chunk resident and area-averaged down to the profile's size. It lives beside the world:
//   <world>/reference/<key>/frame_<NNNN>.png   one per chosen path frame, 8-bit lossless
//   <world>/reference/<key>/reference.json     the key's inputs (below), written last
// The key names everything the images depend on: the world (chunks_checksum of world_manifest.h:
// world.json without its chunk groups, which the reference does not draw), width, height, path frame count, vertical
// field of view, supersampling factor, the chosen frames and the format version; its folder name is readable and ends
// with the CRC-32 of reference.json's text, so different inputs never share a folder. A folder appears complete or not
// at all: it is written under a temporary name and renamed. splat_world leaves reference/ alone (it removes only its
// own gen-<n>/ folders and temporaries), so a regenerated world keeps old references, which no longer match its key.
// GL-free.
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "engine/render/image.h"
#include "sample_game/camera_path.h"
#include "splat_lod/eval/image_metrics.h"

namespace sample_game {

// 2: the world by chunks_checksum; 3: each chosen frame with its successor; 4: every chunk drawn whole
// (version 3 could draw its first frames while the last levels loaded were still fading in); 5: the splats
// of the world's props drawn (an import's far layer; version 4 left them out, in the walk as well)
inline constexpr int kReferenceFormatVersion = 5;
inline constexpr int kDefaultReferenceSupersample = 3;
// The largest side of one render; a larger supersampled frame is drawn in tiles of at most this.
inline constexpr int kReferenceMaxRenderSide = 2048;
inline constexpr const char* kReferenceFolderName = "reference";
// Reference frames per segment (ground, canopy, flyout, overview, return), evenly inside each.
inline constexpr std::array<int, kSegmentCount> kReferenceFramesPerSegment{2, 2, 2, 4, 2};

// The path frames with a reference: per segment kReferenceFramesPerSegment[k] of its frames at
// (i + 0.5) / n of the way through it (fewer when the segment has fewer frames), each with its
// successor f + 1 where the path has one (which may lie in the next segment), so that the profile
// can measure the change between consecutive frames against the reference's (temporal_error,
// frame_strip.h); ascending, without repeats.
std::vector<std::size_t> reference_frame_indices(const std::vector<PathPose>& poses);

struct ReferenceKey {
    std::uint32_t world_checksum = 0;
    std::uint32_t path_checksum = 0;  // of every pose (eye, forward, segment): a path file makes another reference
    int width = 0, height = 0, frames = 0;
    double fov_y_deg = 0.0;
    int supersample = kDefaultReferenceSupersample;
    std::vector<std::size_t> frame_indices;
    int version = kReferenceFormatVersion;

    std::string json() const;         // reference.json's text
    std::string folder_name() const;  // "640x360_f100_s3_<8 hex digits>"
};

// The key of `world`'s reference for these settings (reads world.json; throws naming it).
ReferenceKey reference_key(const std::filesystem::path& world, int width, int height,
                           const std::vector<PathPose>& poses, double fov_y_deg, int supersample);

std::filesystem::path reference_folder(const std::filesystem::path& world, const ReferenceKey& key);
std::filesystem::path reference_frame_file(const std::filesystem::path& folder, std::size_t frame);

struct CachedReference {
    std::filesystem::path folder;
    std::map<int, splat_lod::eval::FloatImage> frames;  // by path frame
};

// None when the key's folder does not exist. A folder that is there but broken (reference.json
// missing or not this key's, a frame missing, unreadable or of the wrong size) is an error naming
// the file, saying to make the reference again with --force.
std::optional<CachedReference> read_reference(const std::filesystem::path& world, const ReferenceKey& key);

// Writes the key's folder (replacing an existing one) from `frames` (each key.width × key.height,
// one per key.frame_indices): into <world>/reference/.tmp-<key>-<pid>/, synced, then renamed.
// Removes temporaries left by killed runs. Throws engine::Error naming the file.
void write_reference(const std::filesystem::path& world, const ReferenceKey& key,
                     const std::map<int, engine::Image>& frames);

}  // namespace sample_game
