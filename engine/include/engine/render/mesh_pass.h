#pragma once
// Draws every mesh component (opaque, depth-tested) into the frame's colour, depth and view
// depth, lit by the scene's directional and ambient lights. GPU copies of mesh assets are made
// on first use and kept while the asset lives.
#include <map>
#include <memory>

#include "engine/render/render_pass.h"

namespace engine {

struct MeshAsset;
struct GpuMesh;

class MeshPass : public RenderPass {
public:
    MeshPass();
    ~MeshPass() override;
    std::string name() const override { return "mesh"; }
    int order() const override { return pass_order::mesh; }
    void execute(FrameContext& frame) override;

    std::size_t gpu_meshes() const { return meshes_.size(); }

private:
    const GpuMesh& gpu_mesh(const std::shared_ptr<const MeshAsset>& asset);
    std::map<const MeshAsset*, std::pair<std::weak_ptr<const MeshAsset>, std::unique_ptr<GpuMesh>>> meshes_;
};

}  // namespace engine
