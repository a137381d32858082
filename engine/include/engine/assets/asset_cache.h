#pragma once
// Loads each asset file once and shares it. Keys are (type, canonical path); anything with a
// loader function can be cached, so plugins cache their own asset types here too.
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <typeindex>

namespace engine {

struct MeshAsset;

class AssetCache {
public:
    template <class T>
    std::shared_ptr<const T> get(const std::filesystem::path& path,
                                 const std::function<std::shared_ptr<const T>(const std::filesystem::path&)>& loader) {
        const Key key{std::type_index(typeid(T)), canonical_key(path)};
        {
            std::lock_guard lock(mutex_);
            if (auto it = entries_.find(key); it != entries_.end())
                return std::static_pointer_cast<const T>(it->second);
        }
        auto loaded = loader(path);  // outside the lock: loads may be slow
        std::lock_guard lock(mutex_);
        entries_[key] = loaded;
        return loaded;
    }

    // glTF 2.0 models (assets/gltf_loader.h).
    std::shared_ptr<const MeshAsset> mesh(const std::filesystem::path& path);

    void clear();
    std::size_t size() const;

private:
    using Key = std::pair<std::type_index, std::string>;
    static std::string canonical_key(const std::filesystem::path& path);
    mutable std::mutex mutex_;
    std::map<Key, std::shared_ptr<const void>> entries_;
};

}  // namespace engine
