// The drop-in LOD's cache key and folder, and the background bake that fills the cache.
#include "splat_lod/bake/lod_cache.h"

#include <algorithm>
#include <chrono>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>

#include <sys/resource.h>
#include <unistd.h>
#include <zlib.h>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "engine/core/log.h"
#include "splat_lod/core/splat_io.h"

namespace splat_lod::bake {
namespace fs = std::filesystem;

namespace {

constexpr const char* kCacheName = "splat_engine";

// The bakes alive in this process, for running_bake_lines().
std::mutex& registry_mutex() {
    static std::mutex mutex;
    return mutex;
}
std::vector<const BackgroundBake*>& registry() {
    static std::vector<const BackgroundBake*> bakes;
    return bakes;
}

[[gnu::format(printf, 1, 2)]] std::string format(const char* pattern, ...) {
    char text[512];
    std::va_list values;
    va_start(values, pattern);
    std::vsnprintf(text, sizeof text, pattern, values);
    va_end(values);
    return text;
}

// How many distinct stage names bake_lod() reports for `o`, assuming every coarse level gains Gaussians
// (with two recipes, the refinement's levels also under their own names).
int expected_stages(const BakeOptions& o) {
    const int coarse = std::max(o.coarsest_level - 1, 0);
    const bool refine = o.refine_iterations > 0 && coarse > 0;
    const int recipes = refine && o.choose_recipe ? 2 : 1;
    const int per_recipe = 1 + coarse + 1 + (refine ? coarse + (o.ranges_after_refine ? 1 : 0) + 1 : 0) + 1;
    return recipes * per_recipe + (refine ? 1 : 0) + (recipes == 2 ? coarse : 0);
}

}  // namespace

fs::path lod_cache_folder() {
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg != nullptr && fs::path(xdg).is_absolute())
        return fs::path(xdg) / kCacheName / "lod";
    if (const char* home = std::getenv("HOME"); home != nullptr && fs::path(home).is_absolute())
        return fs::path(home) / ".cache" / kCacheName / "lod";
    engine::fail("the LOD cache: neither XDG_CACHE_HOME nor HOME is an absolute path");
}

std::string bake_settings_text(const BakeSetup& s) {
    const BakeOptions& o = s.options;
    std::string text = format("format %d; cameras %s; capture %s; up %.9g,%.9g,%.9g; forward %.9g,%.9g,%.9g; %dx%d; ",
                              kLodCacheFormatVersion, s.cameras.c_str(), s.capture.c_str(), s.up.x, s.up.y, s.up.z,
                              s.forward.x, s.forward.y, s.forward.z, s.width, s.height);
    text += format("given %d%d%d%d%d%d%d; ", s.given.cells, s.given.enlargement, s.given.pooling, s.given.margin,
                   s.given.axis_ratio, s.given.member, s.given.refine_cameras);
    text += format("levels %d; S_T %.17g; rel %.17g,%.17g; znear %.17g; margin %.17g; axis %.17g; grid %d; ",
                   o.coarsest_level, double(o.rule.size_threshold_px), double(o.rule.rel_min), double(o.rule.rel_max),
                   o.znear, o.view_margin, o.min_axis_ratio, o.grid_cells);
    text += format("cells %d; pooling %d; choose %d; enlargement %.17g; member %d; percentiles %.17g,%.17g; ",
                   static_cast<int>(o.cells), static_cast<int>(o.pooling), o.choose_recipe, o.max_enlargement,
                   o.member_ranges, o.range_low_percentile, o.range_high_percentile);
    text += format("refine %d x %d; rates %.17g,%.17g; clamp %.17g; ranges after %d; seed %llu; ", o.refine_iterations,
                   o.refine_cameras, o.learning_rate_dc, o.learning_rate_opacity, o.logit_clamp, o.ranges_after_refine,
                   static_cast<unsigned long long>(o.seed));
    text += format("background %.17g,%.17g,%.17g", o.background.x, o.background.y, o.background.z);
    return text;
}

std::string lod_cache_name(std::span<const std::uint8_t> input_bytes, const BakeSetup& setup) {
    uLong crc = crc32(0L, Z_NULL, 0);
    uLong adler = adler32(0L, Z_NULL, 0);
    for (std::size_t at = 0; at < input_bytes.size();) {  // zlib takes 32-bit lengths
        const auto n = static_cast<uInt>(std::min<std::size_t>(input_bytes.size() - at, 1u << 30));
        crc = crc32(crc, input_bytes.data() + at, n);
        adler = adler32(adler, input_bytes.data() + at, n);
        at += n;
    }
    const std::string settings = bake_settings_text(setup);
    const uLong settings_crc = crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(settings.data()),
                                     static_cast<uInt>(settings.size()));
    return format("%08lx%08lx-%08lx.lod.ply", crc & 0xffffffffUL, adler & 0xffffffffUL, settings_crc & 0xffffffffUL);
}

BackgroundBake::BackgroundBake(std::shared_ptr<const SplatCloud> fine, fs::path cache_file, BakeSetup setup,
                               std::string name, std::function<void(const std::string&, double)> observer)
    : fine_(std::move(fine)),
      cache_file_(std::move(cache_file)),
      setup_(std::move(setup)),
      name_(std::move(name)),
      observer_(std::move(observer)) {
    setup_.options.progress = nullptr;  // the bake's progress is this object's
    {
        const std::lock_guard lock(registry_mutex());
        registry().push_back(this);
    }
    worker_ = std::thread([this] { run(); });
}

BackgroundBake::~BackgroundBake() {
    {
        const std::lock_guard lock(registry_mutex());
        std::erase(registry(), this);
    }
    cancel();
    if (worker_.joinable()) worker_.join();
}

std::string BackgroundBake::error() const {
    const std::lock_guard lock(mutex_);
    return error_;
}

std::shared_ptr<const SplatCloud> BackgroundBake::result() const {
    const std::lock_guard lock(mutex_);
    return result_;
}

bool BackgroundBake::wait(double seconds) const {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (state() == State::running) {
        if (std::chrono::steady_clock::now() >= until) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return true;
}

// On the worker, from the bake's progress callback: cancels, tells the observer, updates the percentage
// and logs it at every 10 %.
void BackgroundBake::report(const std::string& stage, double fraction) {
    if (cancel_requested_) throw BakeCancelled();
    if (observer_) observer_(stage, fraction);
    // With two recipes the refinement reports its levels under the recipe's name and its own: a stage
    // counts once, by name.
    if (seen_stages_.insert(stage).second) ++stages_seen_;
    const double done = (std::max(stages_seen_ - 1, 0) + fraction) / std::max(stages_expected_, stages_seen_);
    const int percent = std::clamp(static_cast<int>(done * 100.0), 0, 99);
    percent_ = std::max(percent_.load(), percent);
    if (percent_ / 10 == logged_percent_ / 10) return;
    logged_percent_ = percent_;
    engine::log_info(format("splat_lod: baking %s: %d %% (%s)", name_.c_str(), logged_percent_, stage.c_str()));
}

// The finished asset into the cache; a failure is logged and the asset is still handed over (drawn
// this time, baked again next time).
void BackgroundBake::write_cache(const SplatCloud& baked) const {
    try {
        engine::write_file_atomic(cache_file_, encode_inria_ply(baked));
        engine::remove_stale_temporaries(cache_file_);
        engine::log_info("splat_lod: " + name_ + ": levels of detail cached as " + cache_file_.string());
    } catch (const std::exception& e) {
        engine::log_error("splat_lod: " + name_ + ": the levels of detail could not be cached (" + e.what() +
                          "); they are drawn now and baked again on the next load");
    }
}

void BackgroundBake::run() {
    // Below the frames: Linux gives each thread its own nice value, and the bake's helper threads inherit
    // this one's. A failure only leaves the priority as it was.
    (void)::setpriority(PRIO_PROCESS, static_cast<id_t>(::gettid()), 10);
    const auto start = std::chrono::steady_clock::now();
    try {
        engine::log_info("splat_lod: baking " + name_ + " into levels of detail in the background (" +
                         std::to_string(fine_->size()) + " Gaussians); drawn without them until it is done");
        PreparedBake prepared = prepare_bake(*fine_, setup_);
        validate(prepared.options);
        stages_expected_ = expected_stages(prepared.options);
        prepared.options.progress = [this](const std::string& stage, double fraction) { report(stage, fraction); };
        auto baked = std::make_shared<const SplatCloud>(bake_lod(*fine_, prepared.cameras, prepared.options));
        if (cancel_requested_) throw BakeCancelled();
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        engine::log_info(format("splat_lod: baked %s: %zu Gaussians in %.1f s", name_.c_str(), baked->size(), seconds));
        write_cache(*baked);
        {
            const std::lock_guard lock(mutex_);
            result_ = std::move(baked);
        }
        percent_ = 100;
        state_ = State::done;
    } catch (const BakeCancelled&) {
        engine::log_info("splat_lod: the bake of " + name_ + " was cancelled; nothing was cached");
        state_ = State::cancelled;
    } catch (const std::exception& e) {
        {
            const std::lock_guard lock(mutex_);
            error_ = name_ + ": " + e.what();
        }
        engine::log_error("splat_lod: baking " + name_ + " into levels of detail failed: " + e.what() +
                          "; it is drawn without them and nothing was cached");
        state_ = State::failed;
    }
}

std::vector<std::string> running_bake_lines() {
    std::vector<std::string> lines;
    const std::lock_guard lock(registry_mutex());
    for (const BackgroundBake* bake : registry())
        if (bake->state() == BackgroundBake::State::running)
            lines.push_back(format("baking %s: %d %%", bake->name().c_str(), bake->percent()));
    return lines;
}

}  // namespace splat_lod::bake
