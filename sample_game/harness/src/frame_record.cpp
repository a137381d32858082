#include "sample_game/harness/frame_record.h"

#include <charconv>
#include <cstdio>
#include <sstream>
#include <utility>

#include "engine/core/error.h"
#include "engine/core/file_io.h"

namespace sample_game {
namespace {

std::string integer(std::uint64_t value) {
    return std::to_string(value);
}

std::string decimal(double value, int digits) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", digits, value);
    return text;
}

// A GPU span that was not measured stays empty (gnuplot and spreadsheets skip it, not plot 0).
std::string milliseconds(double value) {
    return value < 0.0 ? std::string() : decimal(value, 3);
}

// Where the frame is on the path.
std::vector<FrameColumn> pose_columns() {
    using R = const FrameRecord&;
    return {
        {"run", "lod: streamed with the LOD mode of the settings; baseline: every chunk resident, mode baseline",
         [](R r) { return r.run; }},
        {"frame", "index of the pose along the path (0-based)", [](R r) { return std::to_string(r.frame); }},
        {"segment", "part of the path: ground, canopy, flyout, overview, return",
         [](R r) { return std::string(to_string(r.segment)); }},
        {"t", "position along the path by frame, 0..1", [](R r) { return decimal(r.t, 5); }},
        {"x", "camera position (m)", [](R r) { return decimal(r.eye.x, 2); }},
        {"y", "camera position (m), Y up", [](R r) { return decimal(r.eye.y, 2); }},
        {"z", "camera position (m)", [](R r) { return decimal(r.eye.z, 2); }},
        {"height_m", "camera height above the terrain (m)", [](R r) { return decimal(r.height_above_ground_m, 2); }},
        {"centre_distance_m", "distance from the camera to the world's centre on the ground (m)",
         [](R r) { return decimal(r.distance_to_centre_m, 2); }},
    };
}

// What the frame cost: wall clock, CPU and GPU timers.
std::vector<FrameColumn> time_columns() {
    using R = const FrameRecord&;
    return {
        {"frame_ms", "render() until glFinish() returned, wall clock (the frame's whole cost here)",
         [](R r) { return decimal(r.frame_ms, 3); }},
        {"stream_ms", "ChunkStreamer::update() on the main thread (with --sync-streaming: includes the reads)",
         [](R r) { return decimal(r.stream_update_ms, 3); }},
        {"cpu_record_ms", "renderer CPU time recording the frame's GL commands",
         [](R r) { return decimal(r.cpu_record_ms, 3); }},
        {"gpu_mesh_ms", "GPU timer: mesh pass (props and terrain mesh)",
         [](R r) { return milliseconds(r.gpu_mesh_ms); }},
        {"gpu_splat_ms", "GPU timer: whole splat pass (the steps below plus uploads of new pages)",
         [](R r) { return milliseconds(r.gpu_splat_ms); }},
        {"gpu_project_ms", "GPU timer: splat steps 1a+1b, cluster skipping, cull, LOD selection, projection",
         [](R r) { return milliseconds(r.gpu_project_ms); }},
        {"gpu_scan_ms", "GPU timer: splat step 2, scan of tile counts",
         [](R r) { return milliseconds(r.gpu_scan_ms); }},
        {"gpu_bin_ms", "GPU timer: splat step 3, binning into (depth, tile) keys",
         [](R r) { return milliseconds(r.gpu_bin_ms); }},
        {"gpu_sort_ms", "GPU timer: splat step 4, radix sort", [](R r) { return milliseconds(r.gpu_sort_ms); }},
        {"gpu_ranges_ms", "GPU timer: splat step 5, tile ranges", [](R r) { return milliseconds(r.gpu_ranges_ms); }},
        {"gpu_raster_ms", "GPU timer: splat step 6, tile raster and composite",
         [](R r) { return milliseconds(r.gpu_raster_ms); }},
        {"gpu_upscale_ms", "GPU timer: splat step 7, upscale (empty at render scale 1)",
         [](R r) { return milliseconds(r.gpu_upscale_ms); }},
        {"redraws", "times the frame was drawn again after a key-buffer overflow (timing is of the complete draw)",
         [](R r) { return std::to_string(r.redraws); }},
    };
}

// What the splat pass drew and left out, and the LOD cut.
std::vector<FrameColumn> count_columns() {
    using R = const FrameRecord&;
    return {
        {"considered", "Gaussians resident in the scene", [](R r) { return integer(r.considered); }},
        {"visible", "Gaussians drawn (after culling and LOD selection)", [](R r) { return integer(r.visible); }},
        {"drawn_l1", "Gaussians drawn of LOD level 1 (finest)", [](R r) { return integer(r.drawn_per_level[0]); }},
        {"drawn_l2", "Gaussians drawn of level 2", [](R r) { return integer(r.drawn_per_level[1]); }},
        {"drawn_l3", "Gaussians drawn of level 3", [](R r) { return integer(r.drawn_per_level[2]); }},
        {"drawn_l4", "Gaussians drawn of level 4 (coarsest)", [](R r) { return integer(r.drawn_per_level[3]); }},
        {"skipped", "Gaussians skipped whole clusters at a time (too small to be selected)",
         [](R r) { return integer(r.skipped); }},
        {"culled", "Gaussians culled by the view frustum before projection, whole clusters at a time",
         [](R r) { return integer(r.culled); }},
        {"hidden", "resident Gaussians of chunks or groups the LOD cut does not draw now, dropped before projection",
         [](R r) { return integer(r.hidden); }},
        {"chunks_drawn", "chunks drawn from their own levels (the LOD cut)",
         [](R r) { return integer(r.chunks_drawn); }},
        {"groups_drawn", "chunk groups drawn instead of their chunks (the LOD cut)",
         [](R r) { return integer(r.groups_drawn); }},
        {"unbudgeted", "Gaussians the selection would have drawn without the splat budget (= visible without one)",
         [](R r) { return integer(r.unbudgeted); }},
        {"budget_threshold_px",
         "the size threshold the frame selected with: S_T times the splat budget's factor (S_T without one)",
         [](R r) { return decimal(r.budget_threshold_px, 3); }},
        {"tile_splat_pairs", "keys sorted: (Gaussian, tile) pairs", [](R r) { return integer(r.tile_splat_pairs); }},
    };
}

// The image against the baseline's and the reference.
std::vector<FrameColumn> image_columns() {
    using R = const FrameRecord&;
    return {
        {"psnr_lod_vs_baseline",
         "baseline rows: PSNR (dB) of the LOD run's image of this frame against this one (empty: not compared)",
         [](R r) { return r.psnr_lod_vs_baseline < 0.0 ? std::string() : decimal(r.psnr_lod_vs_baseline, 3); }},
        {"ssim_lod_vs_baseline",
         "baseline rows: SSIM of the LOD run's image of this frame against this one (empty: not compared)",
         [](R r) { return r.ssim_lod_vs_baseline < 0.0 ? std::string() : decimal(r.ssim_lod_vs_baseline, 4); }},
        {"psnr_vs_reference",
         "PSNR (dB) of this row's image against the cached supersampled reference (-1: no reference for this frame)",
         [](R r) { return r.psnr_vs_reference < 0.0 ? std::string("-1") : decimal(r.psnr_vs_reference, 3); }},
        {"ssim_vs_reference", "SSIM of this row's image against the reference (-1: no reference for this frame)",
         [](R r) { return r.ssim_vs_reference < 0.0 ? std::string("-1") : decimal(r.ssim_vs_reference, 4); }},
        {"seam_ratio", "mean abs. error vs the reference within 4 px of projected chunk borders / elsewhere (-1: none)",
         [](R r) { return r.seam_ratio < 0.0 ? std::string("-1") : decimal(r.seam_ratio, 3); }},
        {"seam_ratio_same_distance",
         "seam_ratio against pixels outside the band at the same ground distance (1/16-octave bins; -1: none)",
         [](R r) {
             return r.seam_ratio_same_distance < 0.0 ? std::string("-1") : decimal(r.seam_ratio_same_distance, 3);
         }},
        {"temporal_error",
         "frames f whose f-1 has a reference too: mean over pixels and RGB of |(M_f - M_f-1) - (R_f - R_f-1)|, "
         "0..255, M this run's images, R the reference (-1: none)",
         [](R r) { return r.temporal_error < 0.0 ? std::string("-1") : decimal(r.temporal_error, 3); }},
        {"pop",
         "the same pair: the 99.9th percentile over pixels of that difference averaged over RGB, 0..255 (a switch in "
         "one frame counts whole, a fade over k frames 1/k; -1: none)",
         [](R r) { return r.pop < 0.0 ? std::string("-1") : decimal(r.pop, 3); }},
    };
}

// GPU memory and uploads.
std::vector<FrameColumn> memory_columns() {
    using R = const FrameRecord&;
    return {
        {"resident_bytes", "streamed GPU bytes resident at the end of the frame (streamer's count, whole pages)",
         [](R r) { return integer(r.resident_bytes); }},
        {"props_gpu_bytes", "GPU bytes of the props' splats (an import's far layer; not streamed, whole pages)",
         [](R r) { return integer(r.props_gpu_bytes); }},
        {"gpu_page_bytes", "GPU scene pages in use x bytes per page (equals resident_bytes + props_gpu_bytes)",
         [](R r) { return integer(r.gpu_page_bytes); }},
        {"gpu_total_bytes", "all GPU buffers of the splat pass: scene capacity plus per-frame buffers",
         [](R r) { return integer(r.gpu_total_bytes); }},
        {"gpu_scene_bytes", "of gpu_total_bytes, the GPU scene's buffers (their capacity)",
         [](R r) { return integer(r.gpu_scene_bytes); }},
        {"gpu_frame_bytes", "of gpu_total_bytes, the per-frame buffers and low-resolution images",
         [](R r) { return integer(r.gpu_frame_bytes); }},
        {"selection_runs",
         "times the splat pass ran its selection (more than 1: the projected splats outgrew their buffer, or a strip "
         "was split)",
         [](R r) { return integer(r.selection_runs); }},
        {"strips", "strips of tile rows the splat pass drew the frame in (its frame memory limit)",
         [](R r) { return integer(r.strips); }},
        {"upload_bytes", "bytes the streamer handed to the GPU this frame (held to the upload budget)",
         [](R r) { return integer(r.stream_upload_bytes); }},
        {"gpu_upload_bytes",
         "bytes the GPU scene sent this frame: new pages plus a 48-byte cluster record per freed page",
         [](R r) { return integer(r.gpu_upload_bytes); }},
    };
}

// Chunks by state (the census).
std::vector<FrameColumn> chunk_state_columns() {
    using R = const FrameRecord&;
    return {
        {"chunks_absent", "chunks whose least advanced needed level is not loaded or requested",
         [](R r) { return integer(r.chunks.absent); }},
        {"chunks_requested", "... is being read", [](R r) { return integer(r.chunks.requested); }},
        {"chunks_loaded", "... is read and waits for upload", [](R r) { return integer(r.chunks.loaded); }},
        {"chunks_partial", "... is partly uploaded", [](R r) { return integer(r.chunks.partial); }},
        {"chunks_resident", "chunks with every needed level resident", [](R r) { return integer(r.chunks.resident); }},
    };
}

std::vector<FrameColumn> make_columns() {
    using R = const FrameRecord&;
    std::vector<FrameColumn> c;
    for (auto part : {pose_columns, time_columns, count_columns, image_columns, memory_columns, chunk_state_columns})
        for (FrameColumn& column : part()) c.push_back(std::move(column));
    for (int level = 0; level <= 4; ++level)
        c.push_back({"chunks_finest_l" + std::to_string(level),
                     level == 0 ? std::string("chunks with nothing resident")
                                : "chunks resident down to level " + std::to_string(level) + " (levels 4.." +
                                      std::to_string(level) + ")",
                     [level](R r) { return integer(r.chunks.finest_resident[static_cast<std::size_t>(level)]); }});
    c.push_back({"chunks_failed", "chunks marked failed", [](R r) { return integer(r.chunks.failed); }});
    c.push_back({"failures_total", "chunk failures reported so far", [](R r) { return integer(r.failures_total); }});
    c.push_back({"gpu_fog_ms", "GPU timer: the distance fog post pass (with --fog)",
                 [](R r) { return milliseconds(r.gpu_fog_ms); }});
    c.push_back({"stereo_frame_ms", "with --stereo: the same frame as a stereo pair, both eyes to the GPU's finish",
                 [](R r) { return milliseconds(r.stereo_frame_ms); }});
    c.push_back({"stereo_eye_psnr",
                 "with --stereo: the lower of the eyes' PSNR against a mono render from that "
                 "eye with its own selection (dB; inf: identical; -1: none)",
                 [](R r) { return r.stereo_eye_psnr < 0.0 ? std::string("-1") : decimal(r.stereo_eye_psnr, 3); }});
    c.push_back({"switch_pop",
                 "with --switch-pops: the 99.9th percentile over pixels of |this frame - this frame drawn with the "
                 "frame before's selection| (0..255; -1: none)",
                 [](R r) { return r.switch_pop < 0.0 ? std::string("-1") : decimal(r.switch_pop, 3); }});
    return c;
}

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> fields;
    std::string field;
    std::istringstream in(line);
    while (std::getline(in, field, ',')) fields.push_back(field);
    if (!line.empty() && line.back() == ',') fields.emplace_back();
    return fields;
}

}  // namespace

const std::vector<FrameColumn>& frame_columns() {
    static const std::vector<FrameColumn> columns = make_columns();
    return columns;
}

void write_frames_csv(const std::filesystem::path& path, const std::vector<FrameRecord>& records,
                      const std::string& title) {
    std::ostringstream out;
    out << "# " << title << "\n# columns:\n";
    for (const auto& column : frame_columns()) out << "#   " << column.name << ": " << column.meaning << "\n";
    std::string header;
    for (const auto& column : frame_columns()) header += (header.empty() ? "" : ",") + column.name;
    out << header << "\n";
    for (const auto& record : records) {
        std::string row;
        for (std::size_t i = 0; i < frame_columns().size(); ++i)
            row += (i ? "," : "") + frame_columns()[i].value(record);
        out << row << "\n";
    }
    engine::write_text_file_atomic(path, out.str());
}

CsvTable read_csv(const std::filesystem::path& path) {
    CsvTable table;
    table.source = path;
    std::istringstream in(engine::read_text_file(path));
    std::string line;
    int line_number = 0;
    while (std::getline(in, line)) {
        ++line_number;
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::string> fields = split(line);
        if (table.header.empty()) {
            table.header = std::move(fields);
            continue;
        }
        if (fields.size() != table.header.size())
            engine::fail(path.string() + ": line " + std::to_string(line_number) + ": " +
                         std::to_string(fields.size()) + " fields, the header has " +
                         std::to_string(table.header.size()));
        table.rows.push_back(std::move(fields));
    }
    if (table.header.empty()) engine::fail(path.string() + ": no header row");
    return table;
}

std::size_t CsvTable::column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i)
        if (header[i] == name) return i;
    std::string names;
    for (const auto& h : header) names += (names.empty() ? "" : ", ") + h;
    engine::fail(source.string() + ": no column '" + name + "' (columns: " + names + ")");
}

double CsvTable::number(std::size_t row, const std::string& name) const {
    const std::string& text = rows.at(row).at(column(name));
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size())
        engine::fail(source.string() + ": data row " + std::to_string(row + 1) + ", column '" + name + "': '" + text +
                     "' is not a number");
    return value;
}

}  // namespace sample_game
