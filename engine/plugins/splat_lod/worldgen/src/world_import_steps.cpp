// The steps of an import that a whole run, a shard and the merge share (world_import_steps.h).
#include "world_import_steps.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <optional>
#include <span>
#include <sstream>
#include <system_error>

#include "chunk_cameras.h"
#include "engine/core/error.h"
#include "engine/core/process_memory.h"
#include "splat_lod/core/cloud_transform.h"
#include "splat_lod/core/gaussian_extent.h"
#include "splat_lod/core/parallel_for.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/core/training_cameras.h"
#include "splat_lod/core/world_lock.h"
#include "world_folder.h"

namespace splat_lod::world {
namespace {

namespace fs = std::filesystem;

constexpr std::uint64_t kSampleMax = std::uint64_t{1} << 20;
// Resident bytes a single-threaded chunk bake is taken to hold per Gaussian of its chunk, and per bake
// (camera images, refinement buffers): an estimate, not a measured bound; it held on the runs of
// docs/results.md (the re-imported default world peaked at 1.95 GB under a 2 GiB cap, two bakes of up
// to 106k Gaussians at once).
constexpr std::uint64_t kBakeBytesPerGaussian = 3072;
constexpr std::uint64_t kBakeFixedBytes = std::uint64_t{96} << 20;
constexpr std::uint64_t kBaseBytes = std::uint64_t{192} << 20;  // the program, the survey sample
constexpr const char* kFarLayerMesh = "meshes/far_layer.glb";

void check(const ImportOptions& o) {
    if (o.capture.empty()) engine::fail("world import: no capture given");
    if (o.output.empty()) engine::fail("world import: no output folder given");
    if (o.memory_bytes < (std::uint64_t{256} << 20))
        engine::fail("world import: --memory " + std::to_string(o.memory_bytes >> 20) +
                     " MiB is below the 256 MiB needed");
    if (o.max_chunk_gaussians < 1024) engine::fail("world import: at least 1024 Gaussians per chunk");
    if (o.bake_width % 64 != 0 || o.bake_height % 64 != 0 || o.bake_width <= 0 || o.bake_height <= 0)
        engine::fail("world import: bake camera sizes must be positive multiples of 64");
    if (o.up && !(glm::length(*o.up) > 0.0f && std::isfinite(glm::length(*o.up))))
        engine::fail("world import: --up must be a non-zero finite vector");
}

void report(const ImportOptions& o, const std::string& stage, std::size_t done, std::size_t total,
            Clock::time_point start, std::uint64_t gaussians = 0) {
    if (o.progress) o.progress({stage, done, total, gaussians, seconds_since(start), -1.0});
}

// Sorts a part's Gaussians into the bins, the far layer, or the counts of what is dropped.
void bin_part(SplatCloud& part, const CaptureFrame& frame, ChunkBins& bins, FarLayer& far, ImportSummary& s,
              const CellFilter& keep) {
    for (std::size_t i = 0; i < part.size(); ++i) {
        const double extent = gaussian_extent(part.log_scales[i], part.opacity_logits[i]);
        if (!(extent > 0.0)) {
            ++s.invisible;
            continue;
        }
        const double reach = gaussian_reach(part.log_scales[i], part.opacity_logits[i]);
        if (!(reach >= frame.degenerate_extent)) {
            ++s.degenerate;
            continue;
        }
        glm::ivec2 cell;
        const bool huge_one = reach > frame.huge_extent;
        if (huge_one || !frame.cell_of(part.positions[i], cell)) {
            ++(huge_one ? s.far_huge : s.far_outside);
            far.add(part, i, static_cast<float>(reach * opacity_from_logit(part.opacity_logits[i])));
            continue;
        }
        int span = 0;
        cell = frame.chunk_of(cell, span);  // bins are named by their chunk's lowest cell
        if (keep && !keep(cell)) continue;  // another shard's chunk
        bins.add(cell, part, i);
        ++s.binned;
    }
}

int bake_threads(const ImportOptions& o, std::uint64_t largest_chunk) {
    const std::uint64_t per_bake = kBakeFixedBytes + largest_chunk * kBakeBytesPerGaussian;
    const std::uint64_t room = o.memory_bytes > kBaseBytes ? o.memory_bytes - kBaseBytes : 0;
    const int fit = static_cast<int>(std::max<std::uint64_t>(1, room / per_bake));
    return std::min(reference::detail::resolve_thread_count(o.threads), fit);
}

// Whether some camera has some Gaussian's centre in front of it and inside its image: a bake needs one.
// A chunk of a few stray Gaussians far above or below the ground grid can be out of every ring's view.
bool any_camera_sees(const SplatCloud& fine, const std::vector<eval::CameraPose>& poses, float aspect, float znear) {
    return std::any_of(poses.begin(), poses.end(), [&](const eval::CameraPose& pose) {
        return points_seen(pose, fine.positions, aspect, znear) > 0;
    });
}

// Bakes one chunk from the training cameras that see it well, else from the rings, or writes it unbaked.
ChunkResult bake_bin(const ChunkBake& how, const WorldOptions& w, const ImportPlan& plan, const GroundHeight& height,
                     const SplatCloud& fine, const fs::path& file, const glm::ivec2& cell) {
    int span = 0;
    plan.frame.chunk_of(cell, span);
    ChunkSquare square;
    square.lo = glm::vec2(cell) * plan.frame.chunk_size;
    square.hi = square.lo + glm::vec2(plan.frame.chunk_size * static_cast<float>(1 << span));
    const float aspect = static_cast<float>(w.bake_width) / static_cast<float>(w.bake_height);
    auto poses = chunk_training_poses(plan.training, fine.positions, square, aspect, w.bake.znear);
    const bool training = poses.size() >= 4;
    if (!training) poses = capture_chunk_camera_poses(height, square, plan.frame.scale(), plan.frame.aerial);
    ChunkResult result;
    if (any_camera_sees(fine, poses, aspect, w.bake.znear)) {
        result = bake_chunk(how, fine, poses, w.output, file, cell);
        result.from_training_cameras = training;
    } else {  // kept as it is: its Gaussians are drawn from any distance, like a prop's
        write_chunk(how, fine, w.output, file, cell, result);
        result.unbaked = true;
    }
    result.entry.span = span;
    return result;
}

std::vector<ChunkResult> bake_bins(const ImportOptions& o, const WorldOptions& w, const ImportPlan& plan,
                                   const GroundGrid& ground, const ChunkBins& bins, const fs::path& generation,
                                   Clock::time_point start) {
    const std::vector<glm::ivec2> cells = bins.cells();
    std::vector<ChunkResult> results(cells.size());
    const ChunkBake how{w.bake, w.bake_width, w.bake_height, stream_level_rule(w), w.chunk_codec};
    const GroundHeight height = [&](float x, float z) { return ground.height(x, z, plan.frame.size()); };
    std::mutex mutex;
    std::size_t done = 0;
    std::uint64_t gaussians = 0, baked = 0, total = 0;
    for (const glm::ivec2& cell : cells) total += bins.count(cell);
    const auto chunks_start = Clock::now();
    report(o, "chunks", 0, cells.size(), start);
    reference::detail::parallel_for(cells.size(), w.threads, [&](std::size_t k) {
        const glm::ivec2 cell = cells[k];
        try {
            results[k] =
                bake_bin(how, w, plan, height, bins.read(cell), chunk_file(generation, cell, w.chunk_codec), cell);
            bins.remove(cell);
        } catch (const std::exception& e) {
            engine::fail(chunk_id(cell) + ": " + e.what());
        }
        const std::lock_guard lock(mutex);
        gaussians += results[k].entry.prefix_count[0];
        baked += bins.count(cell);
        ++done;
        // The ETA from the Gaussians baked so far: chunks differ in size by orders of magnitude.
        const double seconds = seconds_since(chunks_start);
        if (o.progress)
            o.progress({"chunks", done, cells.size(), gaussians, seconds_since(start),
                        seconds * static_cast<double>(total - baked) /
                            static_cast<double>(std::max<std::uint64_t>(baked, 1))});
    });
    return results;
}

void bin_capture(const ImportOptions& o, const ImportPlan& plan, ChunkBins& bins, FarLayer& far, ImportSummary& s,
                 Clock::time_point start, const CellFilter& keep) {
    for (std::size_t p = 0; p < plan.capture.parts.size(); ++p) {
        SplatCloud part = read_capture_part(plan.capture.parts[p]);
        part.extras.clear();
        part.set_sh_degree(plan.sample.sh_degree);
        transform_cloud(part, plan.frame.rotation, plan.frame.translation);
        bin_part(part, plan.frame, bins, far, s, keep);
        report(o, "binning", p + 1, plan.capture.parts.size(), start, s.binned);
    }
    bins.flush();
    s.bin_flushes = bins.flushes();
}

void add_far_layer(const SplatCloud& far_cloud, const fs::path& root, const fs::path& generation, WorldManifest& m) {
    if (far_cloud.empty()) return;
    write_gltf_splats(root / generation / kFarLayerMesh, far_cloud);
    m.props.push_back({generation / kFarLayerMesh, glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(1.0f)});
}

std::string import_settings(const ImportOptions& o, const WorldOptions& w, const CaptureFrame& frame) {
    std::ostringstream s;
    s << ": " << (frame.aerial ? "aerial" : "ground") << " views, at most " << o.max_chunk_gaussians
      << " per chunk, far layer <= " << o.far_layer_max << "; " << generator_settings(w);
    return s.str();
}

CaptureOrigin capture_origin(const ImportOptions& o, const CaptureFrame& frame) {
    CaptureOrigin origin;
    origin.source = o.capture.string();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) origin.rotation[static_cast<std::size_t>(3 * r + c)] = frame.rotation[c][r];
    origin.translation = {frame.translation.x, frame.translation.y, frame.translation.z};
    return origin;
}

// Raised whenever the import makes other bytes from the same capture and options (a cached import of an
// older version is made again).
constexpr int kImportVersion = 5;

// A checksum of what the import's bytes depend on: the import's version, every file of the capture (path, size,
// modification time; a SOG chunk's whole folder) and every option.
std::string capture_fingerprint(const Capture& capture, const ImportOptions& o) {
    std::ostringstream text;
    std::error_code ec;
    const auto describe = [&](const fs::path& file) {
        text << file.string() << ' ' << fs::file_size(file, ec) << ' '
             << fs::last_write_time(file, ec).time_since_epoch().count() << '\n';
    };
    for (const CapturePart& part : capture.parts) {
        text << part.label() << '\n';
        if (part.kind == CapturePart::Kind::sog_ranges) {
            for (const auto& entry : fs::directory_iterator(part.file.parent_path(), ec)) describe(entry.path());
        } else {
            describe(part.file);
        }
    }
    if (!o.cameras.empty()) {
        text << "cameras\n";
        for (const fs::path& file : eval::training_camera_files(o.cameras)) describe(file);
    }
    text << kImportVersion << ' ' << (o.up ? glm::length(*o.up) : 0.0f) << ' ' << (o.up ? o.up->x : 0.0f) << ' '
         << (o.up ? o.up->y : 0.0f) << ' ' << (o.up ? o.up->z : 0.0f) << ' ' << static_cast<int>(o.views) << ' '
         << o.max_chunk_gaussians << ' ' << o.far_layer_max << ' ' << o.bake_width << 'x' << o.bake_height << ' '
         << o.bake.refine_iterations << ' ' << o.groups << ' ' << o.quadtree;
    const std::string all = text.str();
    char hex[16];
    std::snprintf(hex, sizeof hex, "%08x",
                  checksum(std::span(reinterpret_cast<const std::uint8_t*>(all.data()), all.size())));
    return hex;
}

constexpr const char* kImportGenerator = "splat_lod capture import 1";

// What the survey found, for the summary.
void record_survey(const CaptureSample& sample, const CaptureFrame& frame, ImportSummary& s) {
    s.read = sample.read;
    s.dropped_by_reader = sample.dropped_by_reader;
    s.up = frame.up;
    s.up_source = frame.up_source;
    s.rotation = frame.rotation;
    s.translation = frame.translation;
    s.aerial = frame.aerial;
    s.flatness = frame.height_span / frame.footprint;
    s.coarseness = sample.median_extent / frame.footprint;
    s.chunk_size = frame.chunk_size;
    s.size = frame.size();
    s.scale = frame.scale();
}

}  // namespace

std::size_t cell_index(const CaptureFrame& frame, const glm::ivec2& cell) {
    const int n = frame.chunks_per_side;
    return static_cast<std::size_t>(cell.y + n / 2) * static_cast<std::size_t>(n) +
           static_cast<std::size_t>(cell.x + n / 2);
}

// The ground under each chunk: the 10th percentile of the sample's heights there (or over all chunks).
GroundGrid ground_grid(const CaptureSample& sample, const CaptureFrame& frame) {
    const int n = frame.chunks_per_side;
    std::vector<std::vector<float>> heights(static_cast<std::size_t>(n * n));
    std::vector<float> all;
    for (const glm::vec3& p : sample.positions) {
        const glm::vec3 w = glm::vec3(frame.rotation * glm::dvec3(p) + frame.translation);
        glm::ivec2 cell;
        if (!frame.cell_of(w, cell)) continue;
        heights[cell_index(frame, cell)].push_back(w.y);
        all.push_back(w.y);
    }
    const auto low = [](std::vector<float>& v) {
        const auto k = v.size() / 10;
        std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
        return v[k];
    };
    const float fallback = all.empty() ? 0.0f : low(all);
    GroundGrid ground;
    ground.cells = n;
    for (auto& cell : heights) ground.heights.push_back(cell.size() >= 8 ? low(cell) : fallback);
    return ground;
}

// What the world's own code needs of the import (groups, stream levels, the chunk recipe) at scale σ.
WorldOptions import_world_options(const ImportOptions& o, const CaptureFrame& frame, std::uint64_t largest_chunk,
                                  const fs::path& root) {
    const int threads = bake_threads(o, largest_chunk);
    WorldOptions w;
    w.size_m = frame.size();
    w.chunk_size_m = frame.chunk_size;
    w.threads = threads;
    w.bake = o.bake;
    w.bake.znear = o.bake.znear * frame.scale();  // the near plane scales with the cameras' distances
    w.bake_width = o.bake_width;
    w.bake_height = o.bake_height;
    w.chunk_codec = o.chunk_codec;
    w.terrain_mesh = false;
    for (float& reach : w.stream_reach_min) reach *= frame.scale();
    w.groups.enabled = o.groups;
    w.groups.base_cell_m = frame.scale() * w.groups.base_cell_m;
    w.output = root;
    w.progress = o.progress;
    return w;
}

std::optional<WorldManifest> cached_import(const ImportOptions& o, const std::string& fingerprint) {
    std::error_code ec;
    const fs::path path = o.output / kManifestFileName;
    if (o.force || !fs::exists(path, ec)) return std::nullopt;
    try {
        WorldManifest m = read_world_manifest(path);
        if (m.generator.rfind(std::string(kImportGenerator) + " [" + fingerprint + "]", 0) != 0) return std::nullopt;
        for (const auto* list : {&m.chunks, &m.groups})
            for (const ChunkEntry& c : *list)
                if (fs::file_size(o.output / c.file, ec) != c.file_bytes || ec) return std::nullopt;
        return m;
    } catch (const engine::Error&) {
        return std::nullopt;
    }
}

ImportResult cached_import_result(WorldManifest m, const fs::path& folder, Clock::time_point start) {
    ImportResult result;
    result.manifest = std::move(m);
    result.summary.cached = true;
    summarise_manifest(result.manifest, folder, result.summary.world);
    result.summary.world.cached = true;
    result.summary.world.seconds = seconds_since(start);
    return result;
}

ImportPlan open_import(const ImportOptions& o, ImportSummary& s) {
    check(o);
    ImportPlan plan;
    // A part of a cut PLY takes about 512 bytes per record while it is decoded (SH degree 3).
    plan.capture = open_capture(
        o.capture, o.part_records > 0 ? o.part_records : std::max<std::uint64_t>(4096, o.memory_bytes / 8 / 512));
    s.capture_description = plan.capture.description;
    plan.fingerprint = capture_fingerprint(plan.capture, o);
    return plan;
}

void survey_import(const ImportOptions& o, ImportPlan& plan, ImportSummary& s, Clock::time_point start) {
    const auto stage = Clock::now();
    plan.sample = survey_capture(plan.capture, kSampleMax, [&](std::uint64_t parts) {
        report(o, "survey", parts, plan.capture.parts.size(), start);
    });
    plan.frame = choose_frame(plan.sample, o, o.capture.string());
    if (!o.cameras.empty()) {
        plan.training = eval::read_training_cameras(o.cameras);
        for (eval::CameraPose& pose : plan.training) {  // into the world frame
            pose.eye = glm::vec3(plan.frame.rotation * glm::dvec3(pose.eye) + plan.frame.translation);
            pose.forward = glm::normalize(glm::vec3(plan.frame.rotation * glm::dvec3(pose.forward)));
            pose.up = glm::normalize(glm::vec3(plan.frame.rotation * glm::dvec3(pose.up)));
        }
        s.training_cameras = plan.training.size();
    }
    s.world.stages.push_back({"survey", seconds_since(stage)});
    record_survey(plan.sample, plan.frame, s);
}

WorldManifest import_manifest(const ImportOptions& o, const WorldOptions& w, const ImportPlan& plan,
                              const GroundGrid& ground) {
    WorldManifest m;
    m.seed = 0;
    m.size_m = plan.frame.size();
    m.chunk_size_m = plan.frame.chunk_size;
    m.generator = std::string(kImportGenerator) + " [" + plan.fingerprint + "]" + import_settings(o, w, plan.frame);
    m.stream_levels = stream_level_rule(w);
    m.ground = ground;
    m.capture = capture_origin(o, plan.frame);
    return m;
}

WorldManifest bake_capture(const ImportOptions& o, const ImportPlan& plan, const fs::path& root,
                           const fs::path& generation, const fs::path& bins_folder, const CellFilter& keep,
                           bool far_layer, WorldOptions& w, ImportSummary& s, Clock::time_point start) {
    ChunkBins bins(bins_folder, plan.sample.sh_degree, o.bin_flush_bytes > 0 ? o.bin_flush_bytes : o.memory_bytes / 4);
    FarLayer far(plan.sample.sh_degree, o.far_layer_max);
    bin_capture(o, plan, bins, far, s, start, keep);
    if (!keep && bins.cells().empty()) engine::fail(o.capture.string() + ": no Gaussian lies inside the world's box");
    w = import_world_options(o, plan.frame, bins.largest(), root);
    const GroundGrid ground = ground_grid(plan.sample, plan.frame);
    const auto stage = Clock::now();
    std::vector<ChunkResult> chunks = bake_bins(o, w, plan, ground, bins, generation, start);
    for (const ChunkResult& chunk : chunks) {
        s.unbaked_chunks += chunk.unbaked ? 1 : 0;
        s.merged_chunks += chunk.entry.span > 0 ? 1 : 0;
        s.largest_span = std::max(s.largest_span, chunk.entry.span);
        s.training_camera_chunks += chunk.from_training_cameras ? 1 : 0;
    }
    s.world.stages.push_back(
        {"chunks (bake, write) on " + std::to_string(w.threads) + " threads", seconds_since(stage)});
    std::error_code ec;
    fs::remove_all(bins_folder, ec);

    WorldManifest m = import_manifest(o, w, plan, ground);
    const SplatCloud far_cloud = far.finish();
    s.far_dropped = far.dropped();
    s.far_layer = far_cloud.size();
    if (far_layer) add_far_layer(far_cloud, root, generation, m);
    add_chunk_results(chunks, m, s.world);
    return m;
}

}  // namespace splat_lod::world
