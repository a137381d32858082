#include "engine/assets/asset_cache.h"

#include "engine/assets/mesh_asset.h"

namespace engine {

std::string AssetCache::canonical_key(const std::filesystem::path& path) {
    std::error_code ec;
    const auto canonical = std::filesystem::weakly_canonical(path, ec);
    return ec ? path.lexically_normal().string() : canonical.string();
}

std::shared_ptr<const MeshAsset> AssetCache::mesh(const std::filesystem::path& path) {
    return get<MeshAsset>(
        path, [](const std::filesystem::path& p) { return std::make_shared<const MeshAsset>(load_gltf(p)); });
}

void AssetCache::clear() {
    std::lock_guard lock(mutex_);
    entries_.clear();
}

std::size_t AssetCache::size() const {
    std::lock_guard lock(mutex_);
    return entries_.size();
}

}  // namespace engine
