#pragma once
// The drop-in LOD's cache and its background bake (docs/lod.md, "Drop-in LOD"). A splat component with
// "lod": "auto" draws its trained scene at once; its LOD asset is looked up in the user's cache folder
// under a key of the input's bytes and the bake settings, and when it is missing a BackgroundBake makes
// it on a worker thread and writes it there atomically.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "splat_lod/bake/bake_setup.h"
#include "splat_lod/core/splat_cloud.h"

namespace splat_lod::bake {

// Part of every cache key: raised whenever the bake or the asset format changes what a key stands for.
inline constexpr int kLodCacheFormatVersion = 2;  // 2: the level handover in the header

// $XDG_CACHE_HOME/splat_engine/lod when XDG_CACHE_HOME is an absolute path, else
// $HOME/.cache/splat_engine/lod. Throws engine::Error when neither variable gives one.
std::filesystem::path lod_cache_folder();

// Every setting that decides the bake's output (not the thread count, which does not), with the cache
// format version, as one line of text.
std::string bake_settings_text(const BakeSetup& setup);

// The cache file name of an input: "<crc32><adler32>-<settings>.lod.ply" in hexadecimal, the first two
// zlib's CRC-32 and Adler-32 of the input's bytes (a 64-bit content key), the last the CRC-32 of
// bake_settings_text().
std::string lod_cache_name(std::span<const std::uint8_t> input_bytes, const BakeSetup& setup);

// Thrown through the bake by a cancelled BackgroundBake.
struct BakeCancelled : std::exception {
    const char* what() const noexcept override { return "the bake was cancelled"; }
};

// Bakes `fine` with `setup` on a worker thread and writes the LOD asset to `cache_file` through a
// temporary beside it and a rename (engine::write_file_atomic): a failed, cancelled or killed bake
// leaves no file under that name (a kill during the write may leave a temporary; the next bake of
// the same key removes it). A cache that cannot be written is logged and the bake still succeeds.
// Progress and the outcome go to the engine log, naming `name`. The destructor cancels the bake and
// waits for the worker (the bake checks between its steps).
class BackgroundBake {
public:
    enum class State { running, done, failed, cancelled };

    // `observer`, when set, is called on the worker thread with every progress report of the bake;
    // if it throws, the bake fails with that error (tests use it to fail or cancel midway).
    BackgroundBake(std::shared_ptr<const SplatCloud> fine, std::filesystem::path cache_file, BakeSetup setup,
                   std::string name, std::function<void(const std::string& stage, double fraction)> observer = {});
    ~BackgroundBake();
    BackgroundBake(const BackgroundBake&) = delete;
    BackgroundBake& operator=(const BackgroundBake&) = delete;

    void cancel() { cancel_requested_ = true; }
    State state() const { return state_.load(); }
    int percent() const { return percent_.load(); }  // 0..100, an estimate from the bake's stages
    const std::string& name() const { return name_; }
    const std::filesystem::path& cache_file() const { return cache_file_; }
    // The failure's message once state() is failed.
    std::string error() const;
    // The baked cloud once state() is done (as written to the cache file), else null.
    std::shared_ptr<const SplatCloud> result() const;
    // Waits for the worker to finish; returns false when `seconds` passed first.
    bool wait(double seconds) const;

private:
    void run();
    void report(const std::string& stage, double fraction);
    void write_cache(const SplatCloud& baked) const;

    std::shared_ptr<const SplatCloud> fine_;
    std::filesystem::path cache_file_;
    BakeSetup setup_;
    std::string name_;
    std::function<void(const std::string&, double)> observer_;
    std::atomic<bool> cancel_requested_{false};
    std::atomic<State> state_{State::running};
    std::atomic<int> percent_{0};
    mutable std::mutex mutex_;
    std::string error_;
    std::shared_ptr<const SplatCloud> result_;
    int stages_expected_ = 1, stages_seen_ = 0, logged_percent_ = -1;
    std::set<std::string> seen_stages_;
    std::thread worker_;
};

// One line per bake of this process still running, in the order they started:
// "baking scene.ply: 42 %" (the LOD panel shows them).
std::vector<std::string> running_bake_lines();

}  // namespace splat_lod::bake
