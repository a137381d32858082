#pragma once
// Draws the mesh components (opaque, depth-tested) into the frame's colour, depth and view depth, lit
// by the scene's directional and ambient lights. The early pass, before the plugin passes, draws every
// mesh but the late ones (MeshComponent::late); the late pass, after the plugin passes and before post,
// draws those, each fragment hidden where the view depth the passes before it left is nearer (a copy of
// it, so that the pass can read it while writing its own). Each answers the frame's picks for its own
// meshes by a ray cast against their triangles on the CPU. GPU copies of mesh assets are made on first
// use and kept while the asset lives.
#include <map>
#include <memory>

#include <glm/glm.hpp>

#include "engine/render/picking.h"
#include "engine/render/render_pass.h"

namespace engine {

struct MeshAsset;
struct GpuMesh;
namespace gl {
class Texture;
}

enum class MeshStage { early, late };

class MeshPass : public RenderPass {
public:
    explicit MeshPass(MeshStage stage = MeshStage::early);
    ~MeshPass() override;
    std::string name() const override { return stage_ == MeshStage::early ? "mesh" : "mesh_late"; }
    int order() const override { return stage_ == MeshStage::early ? pass_order::mesh : pass_order::late_mesh; }
    void execute(FrameContext& frame) override;
    // The frame's picks are answered on the CPU as it is drawn (pick_meshes), so always ready.
    PickResult pick_answer(std::uint64_t ticket, bool wait) override;

    std::size_t gpu_meshes() const { return meshes_.size(); }

private:
    const GpuMesh& gpu_mesh(const std::shared_ptr<const MeshAsset>& asset);
    // The late pass's copy of the view depth, kept while the target's size stays the same.
    const gl::Texture& surface_depth(const RenderTarget& target);

    MeshStage stage_;
    PickAnswers answers_;
    std::unique_ptr<gl::Texture> surface_depth_;
    glm::ivec2 surface_depth_size_{0, 0};
    std::map<const MeshAsset*, std::pair<std::weak_ptr<const MeshAsset>, std::unique_ptr<GpuMesh>>> meshes_;
};

}  // namespace engine
