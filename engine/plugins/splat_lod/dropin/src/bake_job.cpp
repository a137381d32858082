// The drop-in LOD's bake (drop_in_jobs.h): the cache lookup when a scene loads, the background bake,
// and the swap between two frames.
#include <algorithm>
#include <system_error>
#include <vector>

#include "drop_in_jobs.h"
#include "engine/assets/asset_cache.h"
#include "engine/core/file_io.h"
#include "engine/core/log.h"
#include "splat_lod/bake/lod_cache.h"
#include "splat_lod/core/splat_io.h"

namespace splat_lod::dropin {
namespace fs = std::filesystem;

namespace {

// The bytes the cache key is made of: the file's, or for a SOG scene (a folder, or its meta.json) those
// of every file in the folder in name order.
std::vector<std::uint8_t> input_bytes(const fs::path& asset) {
    const fs::path folder = fs::is_directory(asset)           ? asset
                            : asset.filename() == "meta.json" ? asset.parent_path()
                                                              : "";
    if (folder.empty()) return engine::read_binary_file(asset);
    std::vector<fs::path> files;
    for (const auto& item : fs::directory_iterator(folder))
        if (item.is_regular_file()) files.push_back(item.path());
    std::sort(files.begin(), files.end());
    std::vector<std::uint8_t> bytes;
    for (const auto& file : files) {
        const std::string label = file.filename().string() + "\n";
        bytes.insert(bytes.end(), label.begin(), label.end());
        const auto content = engine::read_binary_file(file);
        bytes.insert(bytes.end(), content.begin(), content.end());
    }
    return bytes;
}

// A running bake, swapped in by the first frame after it is done.
class BakeJob final : public LodJob {
public:
    explicit BakeJob(std::shared_ptr<bake::BackgroundBake> bake) : bake_(std::move(bake)) {}
    const std::shared_ptr<bake::BackgroundBake>& bake() const { return bake_; }

    bool update(SplatComponent& component, const LodFrame&) override {
        switch (bake_->state()) {
            case bake::BackgroundBake::State::running:
                return true;
            case bake::BackgroundBake::State::done:
                component.cloud = bake_->result();
                engine::log_info("splat_lod: " + bake_->name() + ": drawn with its levels of detail from now on");
                return false;
            case bake::BackgroundBake::State::failed:
            case bake::BackgroundBake::State::cancelled:
                break;
        }
        return false;  // already logged; the trained scene stays
    }

    std::string status() const override {
        return "baking " + bake_->name() + ": " + std::to_string(bake_->percent()) + " %";
    }

private:
    std::shared_ptr<bake::BackgroundBake> bake_;
};

}  // namespace

std::shared_ptr<bake::BackgroundBake> background_bake(const SplatComponent& component) {
    const auto* job = dynamic_cast<const BakeJob*>(component.lod_job.get());
    return job ? job->bake() : nullptr;
}

void start_bake(SplatComponent& component, const DropInLodSettings& settings, engine::AssetCache& assets) {
    const std::string name = component.asset.filename().string();
    fs::path entry;
    try {
        entry = cache_root(settings) / bake::lod_cache_name(input_bytes(component.asset), settings.setup);
    } catch (const std::exception& e) {
        engine::log_warning("splat_lod: " + name + ": no levels of detail (" + e.what() + ")");
        return;
    }
    std::error_code ec;
    if (fs::is_regular_file(entry, ec)) {
        try {
            component.cloud = assets.get<SplatCloud>(
                entry, [](const fs::path& p) { return std::make_shared<const SplatCloud>(load_splat_file(p)); });
            engine::log_info("splat_lod: " + name + ": levels of detail from the cache (" + entry.string() + ")");
            return;
        } catch (const std::exception& e) {
            engine::log_warning("splat_lod: " + name + ": the cached levels of detail are unreadable, baking again (" +
                                e.what() + ")");
        }
    }
    component.lod_job = std::make_shared<BakeJob>(
        std::make_shared<bake::BackgroundBake>(component.cloud, entry, settings.setup, name, settings.observer));
}

}  // namespace splat_lod::dropin
