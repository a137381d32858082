#pragma once
// The ResidencySink that puts streamed chunk levels into a scene: one node with a SplatComponent
// per uploaded part, under a root node the game owns. The splat pass's incremental GPU scene
// (gpu/gpu_scene.h) then uploads exactly that part's pages and frees them when the node goes, so
// the streamer's byte counts (splat_lod/gpu_storage.h, PageLayout) are the GPU's.
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "engine/scene/node.h"
#include "splat_lod/core/world_manifest.h"
#include "splat_lod/stream/stream_interfaces.h"

namespace engine {
class AssetCache;
}

namespace splat_lod::world {

// A world's props and terrain mesh under `parent` (one node per prop, "<file stem> <index>", with the
// prop's transform, and "terrain"): a glTF's triangles as a mesh component (drawn by the mesh pass and
// composited with the splats by depth), its Gaussian splats (an import's far layer) as a splat component
// of at most `sh_degree_cap`. Files are relative to `folder`; errors name them.
void add_world_props(engine::Node& parent, const WorldManifest& manifest, const std::filesystem::path& folder,
                     engine::AssetCache& assets, int sh_degree_cap = kMaxShDegree);

class SceneResidencySink final : public ResidencySink {
public:
    // `root` must outlive the sink; its other children are left alone.
    explicit SceneResidencySink(engine::Node& root, int sh_degree_cap = kMaxShDegree);
    void upload(const LevelPart& part) override;
    void release(const std::string& chunk_id, int level) override;
    // Sets SplatComponent::visible of every node of the chunk or group.
    void show(const std::string& chunk_id, bool visible) override;
    // Sets SplatComponent::opacity of every node of that level.
    void fade(const std::string& chunk_id, int level, float opacity) override;

    std::size_t resident_parts() const;

private:
    engine::Node& root_;
    int sh_degree_cap_;
    std::map<std::pair<std::string, int>, std::vector<engine::Node*>> nodes_;
};

}  // namespace splat_lod::world
