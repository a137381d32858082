#include "drop_in_lod.h"

#include <algorithm>
#include <system_error>
#include <vector>

#include "engine/assets/asset_cache.h"
#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "engine/core/log.h"
#include "engine/scene/scene.h"
#include "splat_lod/bake/lod_cache.h"
#include "splat_lod/core/splat_io.h"

namespace splat_lod {
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

}  // namespace

void start_drop_in_lod(SplatComponent& component, const DropInLodSettings& settings, engine::AssetCache& assets) {
    if (!component.cloud || component.cloud->has_lod_attributes()) return;
    const std::string name = component.asset.filename().string();
    if (const std::string why = settings.world_advice ? settings.world_advice(*component.cloud) : ""; !why.empty()) {
        engine::log_warning("splat_lod: " + name + ": " + why +
                            ": drawn as trained, without levels of detail (baking it as one file would take long and "
                            "serve it badly); make it a streamed world: splat_world --from " +
                            component.asset.string() + " --out <folder> (docs/world_lod.md, \"Importing a capture\")");
        return;
    }
    fs::path entry;
    try {
        const fs::path folder = settings.cache_folder.empty() ? bake::lod_cache_folder() : settings.cache_folder;
        entry = folder / bake::lod_cache_name(input_bytes(component.asset), settings.setup);
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
    component.lod_bake =
        std::make_shared<bake::BackgroundBake>(component.cloud, entry, settings.setup, name, settings.observer);
}

bool SplatComponent::update_lod() {
    if (!lod_bake) return false;
    switch (lod_bake->state()) {
        case bake::BackgroundBake::State::running:
            return false;
        case bake::BackgroundBake::State::done:
            cloud = lod_bake->result();
            engine::log_info("splat_lod: " + lod_bake->name() + ": drawn with its levels of detail from now on");
            lod_bake.reset();
            return true;
        case bake::BackgroundBake::State::failed:
        case bake::BackgroundBake::State::cancelled:
            break;
    }
    lod_bake.reset();  // already logged; the trained scene stays
    return false;
}

void LodSwapPass::execute(engine::FrameContext& frame) {
    for (SplatComponent* component : frame.scene.components<SplatComponent>()) component->update_lod();
}

}  // namespace splat_lod
