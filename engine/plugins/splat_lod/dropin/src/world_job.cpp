// The drop-in LOD's world (drop_in_jobs.h): the capture imported in the background into the cache's
// worlds/ folder, then streamed under the component's node (streamed_world.h).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <thread>

#include <sys/resource.h>
#include <unistd.h>
#include <zlib.h>

#include "drop_in_jobs.h"
#include "engine/core/error.h"
#include "engine/core/log.h"
#include "streamed_world.h"

namespace splat_lod::dropin {
namespace fs = std::filesystem;

namespace {

// The import on its own thread; the destructor cancels it (at its next progress report) and joins.
class BackgroundImport {
public:
    BackgroundImport(world::ImportOptions options, std::string name,
                     std::function<void(const std::string&, double)> observer)
        : name_(std::move(name)), observer_(std::move(observer)) {
        options.progress = [this](const world::WorldProgress& p) { report(p); };
        thread_ = std::thread([this, options = std::move(options)] { run(options); });
    }
    ~BackgroundImport() {
        cancel_ = true;
        thread_.join();
    }
    BackgroundImport(const BackgroundImport&) = delete;
    BackgroundImport& operator=(const BackgroundImport&) = delete;

    bool finished() const { return finished_.load(); }
    bool wait(double seconds) const {
        std::unique_lock lock(mutex_);
        return ended_.wait_for(lock, std::chrono::duration<double>(seconds), [this] { return finished_.load(); });
    }
    // Once finished: whether the world is there (a failure was logged).
    bool imported() const { return imported_.load(); }
    std::string line() const {
        const std::lock_guard lock(mutex_);
        return "importing " + name_ + " as a streamed world: " + stage_;
    }

private:
    void report(const world::WorldProgress& p) {
        if (cancel_) engine::fail("cancelled");
        const double fraction = p.chunks_total > 0 ? static_cast<double>(p.chunks_done) / p.chunks_total : 0.0;
        if (observer_) observer_("import: " + p.stage, fraction);
        const std::lock_guard lock(mutex_);
        stage_ = p.stage + (p.chunks_total > 0 ? " " + std::to_string(static_cast<int>(100.0 * fraction)) + " %" : "");
    }
    void run(const world::ImportOptions& options) {
        // Below the frames, as the bake: each Linux thread has its own nice value and the import's helper
        // threads inherit this one's.
        (void)::setpriority(PRIO_PROCESS, static_cast<id_t>(::gettid()), 10);
        bool imported = false;
        try {
            const world::ImportResult result = world::import_world(options);
            engine::log_info("splat_lod: " + name_ +
                             (result.summary.cached ? ": its streamed world is " : ": imported as ") +
                             options.output.string() + (result.summary.cached ? " already" : ""));
            imported = true;
        } catch (const std::exception& e) {
            if (!cancel_) engine::log_warning("splat_lod: " + name_ + ": not streamed as a world (" + e.what() + ")");
        }
        {
            const std::lock_guard lock(mutex_);
            imported_ = imported;
            finished_ = true;
        }
        ended_.notify_all();
    }

    std::string name_;
    std::function<void(const std::string&, double)> observer_;
    std::atomic<bool> cancel_{false}, finished_{false}, imported_{false};
    mutable std::mutex mutex_;
    mutable std::condition_variable ended_;
    std::string stage_ = "starting";
    std::thread thread_;
};

class WorldJob final : public LodJob {
public:
    WorldJob(const SplatComponent& component, const DropInLodSettings& settings, engine::AssetCache& assets,
             fs::path folder)
        : settings_(settings), assets_(assets), folder_(std::move(folder)), name_(component.asset.filename().string()) {
        world::ImportOptions options = settings.import;
        options.capture = component.asset;
        options.output = folder_;
        import_ = std::make_unique<BackgroundImport>(options, name_, settings.observer);
    }

    bool update(SplatComponent& component, const LodFrame& frame) override {
        if (import_ && !import_->finished()) return true;
        if (import_ && !open(component)) return false;
        world_->update(component, frame);
        return true;  // streams as long as the component lives
    }

    std::string status() const override {
        if (import_) return import_->line();
        if (world_ && world_->holding())
            return "streaming " + name_ + ": loading the first view (the trained scene meanwhile)";
        return "";
    }

    WorldStatus world_status() const {
        WorldStatus s;
        s.folder = folder_;
        if (import_) {
            s.state = WorldStatus::State::importing;  // until the frame after it ended opens the world
        } else if (world_) {
            s.state = world_->holding() ? WorldStatus::State::holding : WorldStatus::State::streaming;
            s.streamer = &world_->streamer();
        }
        return s;
    }
    bool wait(double seconds) const { return !import_ || import_->wait(seconds); }

private:
    // The import has ended: the world under the component's node, or false (the trained scene stays).
    bool open(SplatComponent& component) {
        const bool imported = import_->imported();  // else the import logged why not
        import_.reset();
        if (!imported) return false;
        try {
            world_ = std::make_unique<StreamedWorld>(component, folder_, settings_, assets_);
            return true;
        } catch (const std::exception& e) {
            engine::log_warning("splat_lod: " + name_ + ": not streamed as a world (" + e.what() + ")");
            return false;
        }
    }

    DropInLodSettings settings_;
    engine::AssetCache& assets_;
    fs::path folder_;
    std::string name_;
    std::unique_ptr<BackgroundImport> import_;
    std::unique_ptr<StreamedWorld> world_;
};

}  // namespace

fs::path world_cache_folder(const fs::path& cache_folder, const fs::path& capture) {
    const std::string path = fs::absolute(capture).lexically_normal().string();
    const auto crc =
        static_cast<unsigned>(crc32(0L, reinterpret_cast<const Bytef*>(path.data()), static_cast<uInt>(path.size())));
    char hash[9];
    std::snprintf(hash, sizeof hash, "%08x", crc);
    // A streamed SOG or SOG folder is named by its folder ("lod-meta" says nothing).
    const bool generic = capture.filename() == "lod-meta.json" || capture.filename() == "meta.json";
    const std::string name = generic ? capture.parent_path().filename().string() : capture.stem().string();
    return cache_folder / "worlds" / (name + "-" + hash);
}

WorldStatus world_status(const SplatComponent& component) {
    const auto* job = dynamic_cast<const WorldJob*>(component.lod_job.get());
    return job ? job->world_status() : WorldStatus{};
}

bool wait_for_import(const SplatComponent& component, double seconds) {
    const auto* job = dynamic_cast<const WorldJob*>(component.lod_job.get());
    return !job || job->wait(seconds);
}

void start_world(SplatComponent& component, const DropInLodSettings& settings, engine::AssetCache& assets,
                 const std::string& why) {
    const std::string name = component.asset.filename().string();
    fs::path folder;
    try {
        folder = world_cache_folder(cache_root(settings), component.asset);
    } catch (const std::exception& e) {
        engine::log_warning("splat_lod: " + name + ": no levels of detail (" + e.what() + ")");
        return;
    }
    engine::log_info("splat_lod: " + name + ": " + why + ": streamed as a world, imported in the background into " +
                     folder.string() + " (the trained scene is drawn meanwhile)");
    component.lod_job = std::make_shared<WorldJob>(component, settings, assets, folder);
}

}  // namespace splat_lod::dropin
