#include "sample_game/harness/reference_run.h"

#include <algorithm>
#include <map>

#include "engine/core/error.h"
#include "engine/render/render_target.h"
#include "formatted.h"
#include "progress.h"
#include "sample_game/game_world.h"
#include "sample_game/harness/profile_run.h"
#include "sample_game/world_path.h"
#include "splat_lod/splat_lod_plugin.h"

namespace sample_game {
namespace {

// Tiles of at most `max_side` along one side of `length` pixels, as even as whole pixels allow.
std::vector<std::pair<int, int>> spans(int length, int max_side) {
    const int count = (length + max_side - 1) / max_side;
    std::vector<std::pair<int, int>> out;
    for (int k = 0; k < count; ++k) {
        const int begin = k * length / count, end = (k + 1) * length / count;
        out.push_back({begin, end - begin});
    }
    return out;
}

}  // namespace

void validate(const ReferenceOptions& o) {
    validate_path_run(o.world, o.width, o.height, o.frames);
    if (o.supersample < 3 || o.supersample > 8)
        engine::fail("sample_game_harness: --supersample must be 3..8 (pixels per side averaged into one), got " +
                     std::to_string(o.supersample));
    if (o.max_render_side < 16)
        engine::fail("sample_game_harness: reference: the largest render side must be at least 16");
    validate(o.settings);
    require_world_folder(o.world);
}

namespace {

// Below this side a tile that does not fit the key buffer is not split further (the error stands).
constexpr int kMinSplitSide = 64;

struct TiledDraw {
    engine::Engine& engine;
    const engine::Scene& scene;
    const engine::CameraView& camera;
    splat_lod::eval::FloatImage& whole;
    std::map<std::pair<int, int>, engine::RenderTarget> targets;  // one per tile size

    // Draws the window [x0, x0 + w) × [y0, y0 + h); a window whose (Gaussian, tile) pairs do not fit
    // the largest key buffer the sort allows is drawn as four quarters instead.
    void window(int x0, int y0, int w, int h) {
        const engine::CameraView tile = engine::tile_view(camera, {x0, y0}, {w, h});
        auto target = targets.try_emplace({w, h}, w, h).first;
        try {
            splat_lod::render_complete(engine, scene, tile, target->second);
        } catch (const engine::Error&) {
            if (std::min(w, h) < 2 * kMinSplitSide) throw;
            for (const auto& [dx, dw] : spans(w, (w + 1) / 2))
                for (const auto& [dy, dh] : spans(h, (h + 1) / 2)) window(x0 + dx, y0 + dy, dw, dh);
            return;
        }
        const engine::Image image = target->second.read_color();
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int c = 0; c < 3; ++c)
                    whole.at(x0 + x, y0 + y, c) = static_cast<float>(image.pixel(x, y)[c]) / 255.0f;
    }
};

}  // namespace

splat_lod::eval::FloatImage render_tiled(engine::Engine& engine, const engine::Scene& scene,
                                         const engine::CameraView& camera, int max_side) {
    splat_lod::eval::FloatImage whole = splat_lod::eval::make_float_image(camera.width, camera.height);
    TiledDraw draw{engine, scene, camera, whole, {}};
    for (const auto& [y0, h] : spans(camera.height, max_side))
        for (const auto& [x0, w] : spans(camera.width, max_side)) draw.window(x0, y0, w, h);
    return whole;
}

ReferenceOutcome make_reference(const ReferenceOptions& o, std::FILE* progress) {
    validate(o);
    const auto start = Clock::now();
    engine::Engine engine;
    engine.plugins().add_static(splat_lod::make_plugin());
    // The reference is the truth the profile scores against: the Gaussians as trained, full floats.
    GameSettings settings = o.settings;
    settings.gpu_storage = splat_lod::GpuStorage::full;
    // Drawn in one piece: a supersampled frame in strips (the game's frame memory limit) would be the same
    // to within a step of 255 (one-word keys), at the cost of many strips.
    settings.frame_memory_bytes = 0;
    GameWorld world(engine, o.world, settings);
    const std::vector<PathPose> poses = world.path(o.frames);
    const ReferenceKey key = reference_key(o.world, o.width, o.height, poses, o.settings.fov_y_deg, o.supersample);
    ReferenceOutcome outcome;
    outcome.folder = reference_folder(o.world, key);
    outcome.frames = key.frame_indices;
    if (!o.force && read_reference(o.world, key)) {
        outcome.cached = true;
        outcome.seconds = seconds_since(start);
        outcome.text = formatted(
            "sample_game_harness: reference: %s is there already (%zu frames, checked); nothing to do "
            "(--force makes it again)\n",
            outcome.folder.string().c_str(), key.frame_indices.size());
        return outcome;
    }

    Progress loading(progress, "reference: chunks loaded", world.manifest().chunks.size());
    outcome.load_seconds = world.load_whole_world([&](std::size_t done, std::size_t) { loading.step(done, ""); });
    // The defaults (full resolution, no level colours, no filter or budget) in baseline mode: the
    // reference depends on none of the game's LOD settings.
    plugin_msgs::LodSettings lod;
    lod.rule.mode = plugin_msgs::LodMode::baseline;
    engine.bus().publish(lod);

    const int s = o.supersample;
    std::map<int, engine::Image> frames;
    const auto draw_start = Clock::now();
    Progress report(progress, "reference frame", key.frame_indices.size());
    for (std::size_t k = 0; k < key.frame_indices.size(); ++k) {
        const PathPose& pose = poses[key.frame_indices[k]];
        const engine::CameraView camera = world.camera(pose, s * o.width, s * o.height);
        const auto fine = render_tiled(engine, world.scene(), camera, o.max_render_side);
        frames[static_cast<int>(key.frame_indices[k])] =
            splat_lod::eval::to_rgba8(splat_lod::eval::area_average(fine, s));
        report.step(k + 1, formatted(" (path frame %zu, %s, %dx%d averaged %dx%d)", key.frame_indices[k],
                                     std::string(to_string(pose.segment)).c_str(), s * o.width, s * o.height, s, s));
    }
    const double draw_seconds = seconds_since(draw_start);
    write_reference(o.world, key, frames);
    outcome.seconds = seconds_since(start);
    outcome.text = formatted(
        "sample_game_harness: reference: %zu frames (%dx%d, %dx supersampled, baseline mode, every chunk resident) in "
        "%s; "
        "%.0f s in all (loading every chunk %.0f s, drawing %.0f s, %.1f s per frame)\n",
        key.frame_indices.size(), o.width, o.height, s, outcome.folder.string().c_str(), outcome.seconds,
        outcome.load_seconds, draw_seconds,
        draw_seconds / static_cast<double>(std::max<std::size_t>(1, frames.size())));
    return outcome;
}

}  // namespace sample_game
