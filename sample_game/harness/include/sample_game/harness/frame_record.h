#pragma once
// One profiled frame of the walkthrough, and its CSV form. The columns are listed once
// (frame_columns()) with what each means; the CSV writer puts that list in the file's comment
// header, the README repeats it, and the reader used by the summary and the tests parses by name.
#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "sample_game/camera_path.h"
#include "sample_game/chunk_census.h"

namespace sample_game {

struct FrameRecord {
    std::string run = "lod";  // "lod" (streamed, LOD mode of the settings) or "baseline"
    int frame = 0;            // index along the path
    Segment segment = Segment::ground;
    float t = 0.0f;
    glm::vec3 eye{0.0f};
    float height_above_ground_m = 0.0f;
    float distance_to_centre_m = 0.0f;

    double frame_ms = 0.0;          // render() until glFinish() returned: what the frame cost (CPU clock)
    double stream_update_ms = 0.0;  // ChunkStreamer::update() on the main thread
    double cpu_record_ms = 0.0;     // the renderer's CPU time recording the frame (FrameStatistics)
    // GPU timer spans of the frame (GL_TIMESTAMP; on llvmpipe also CPU work), −1 when absent.
    double gpu_mesh_ms = -1.0, gpu_splat_ms = -1.0, gpu_project_ms = -1.0, gpu_scan_ms = -1.0, gpu_bin_ms = -1.0,
           gpu_sort_ms = -1.0, gpu_ranges_ms = -1.0, gpu_raster_ms = -1.0, gpu_upscale_ms = -1.0, gpu_fog_ms = -1.0;
    int redraws = 0;  // frames drawn again because the key buffer overflowed (it grows after each)

    std::uint64_t considered = 0, visible = 0, skipped = 0, tile_splat_pairs = 0;
    std::uint64_t culled = 0;          // Gaussians in clusters outside the view frustum, dropped before projection
    std::uint64_t hidden = 0;          // resident Gaussians of chunks or groups outside the LOD cut (not drawn)
    std::uint64_t unbudgeted = 0;      // what the selection would draw without the splat budget (= visible without one)
    double budget_threshold_px = 0.0;  // the size threshold the frame selected with (S_T × the budget's β)
    std::array<std::uint64_t, 4> drawn_per_level{};  // visible per LOD level 1..4

    std::uint64_t resident_bytes = 0;   // the streamer's count of resident GPU bytes (pages)
    std::uint64_t props_gpu_bytes = 0;  // the splats of the world's props (an import's far layer), always resident
    std::uint64_t gpu_page_bytes = 0;   // the GPU scene's pages in use × bytes per page (must equal the two above)
    std::uint64_t gpu_total_bytes = 0;  // everything the splat pass holds: scene buffers' capacity + frame buffers
    std::uint64_t gpu_scene_bytes = 0;  // of which the scene buffers' capacity (SplatMemory::scene_bytes)
    std::uint64_t gpu_frame_bytes = 0;  // and the per-frame buffers (SplatMemory::frame_bytes)
    int selection_runs = 1;             // 2: the frame's steps 1–2 ran again (SplatMemory::selection_runs)
    int strips = 1;                     // strips of tile rows the frame was drawn in (SplatMemory::strips)
    std::uint64_t stream_upload_bytes =
        0;                               // bytes the streamer handed to the GPU side this frame (the budgeted amount)
    std::uint64_t gpu_upload_bytes = 0;  // bytes the GPU scene sent this frame (+48 per freed page's cluster record)
    ChunkCensus chunks;
    std::uint32_t chunks_drawn = 0, groups_drawn = 0;  // the LOD cut: chunks and chunk groups drawn
    std::uint64_t failures_total = 0;                  // chunk failures so far
    // Baseline rows only: the LOD run's image of the same path frame against this one (every chunk
    // resident, `baseline` mode) as the reference; −1 where not compared.
    double psnr_lod_vs_baseline = -1.0, ssim_lod_vs_baseline = -1.0;
    // Rows of a frame with a cached reference (reference_cache.h): this row's image against it; −1
    // where the frame has none.
    double psnr_vs_reference = -1.0, ssim_vs_reference = -1.0;
    // LOD rows of a reference frame: the image's mean absolute error against the reference within
    // ±4 px of the projected chunk borders divided by that elsewhere (chunk_borders.h); −1 on
    // baseline rows, frames without a reference, and frames without border or error to compare.
    double seam_ratio = -1.0;
    // The same with the distance held fixed (seam_ratio_same_distance in chunk_borders.h): the band's
    // error over that of pixels outside it whose ground is as far away; −1 where seam_ratio is.
    double seam_ratio_same_distance = -1.0;
    // Rows whose frame f and predecessor f − 1 both have a reference, drawn by this row's run: the mean
    // over pixels and RGB channels of |(M_f − M_{f−1}) − (R_f − R_{f−1})| in 8-bit units (frame_strip.h;
    // M this run's images, R the reference's): change between consecutive frames that the reference
    // does not have, such as a level popping; −1 elsewhere.
    double temporal_error = -1.0;
    double pop = -1.0;  // the same pair's pop: splat_lod::eval::temporal_pair_pop (−1: none)
    // With --stereo (LOD rows): the frame drawn again as a stereo pair (engine::stereo_eyes, one
    // selection, the centre's), both eyes one after the other to the GPU's finish; and the lower of the two
    // eyes' PSNR against a mono render from that eye with its own selection. −1 without.
    double stereo_frame_ms = -1.0, stereo_eye_psnr = -1.0;
    double switch_pop = -1.0;  // with --switch-pops: the pair (frame − 1, frame)'s switch pop (−1: none)
};

struct FrameColumn {
    std::string name;
    std::string meaning;
    std::function<std::string(const FrameRecord&)> value;
};
const std::vector<FrameColumn>& frame_columns();

// Writes the records as CSV: '#' comment lines naming every column and its meaning, then the
// header row, then one row per record (atomically). Throws engine::Error naming the file.
void write_frames_csv(const std::filesystem::path& path, const std::vector<FrameRecord>& records,
                      const std::string& title);

// A CSV read back as named columns of text (comment lines skipped). Throws engine::Error naming
// the file and line when a row has the wrong number of fields.
struct CsvTable {
    std::filesystem::path source;
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
    // Index of a column; throws engine::Error naming the file's columns when absent.
    std::size_t column(const std::string& name) const;
    double number(std::size_t row, const std::string& name) const;
};
CsvTable read_csv(const std::filesystem::path& path);

}  // namespace sample_game
