#include "engine/render/mesh_pass.h"

#include <engine/mesh_shared.h>  // shaders/engine/mesh_shared.h, shared with GLSL

#include "engine/assets/mesh_asset.h"
#include "engine/gl/compute_step.h"
#include "engine/gl/draw.h"
#include "engine/gl/gpu_timers.h"
#include "engine/gl/objects.h"
#include "engine/gl/shader_library.h"
#include "engine/render/render_target.h"
#include "engine/scene/builtin_components.h"
#include "engine/scene/scene.h"

namespace engine {

struct GpuPrimitive {
    gl::VertexArray vao{gl::NoCreate};
    gl::Buffer vertices{gl::NoCreate};
    gl::Buffer indices{gl::NoCreate};
    GLsizei index_count = 0;
    int material = -1;
    glm::mat4 transform{1.0f};
};

struct GpuMesh {
    std::vector<GpuPrimitive> primitives;
    std::vector<gl::Texture> textures;  // one per MeshAsset image
};

namespace {

GpuPrimitive upload_primitive(const MeshPrimitive& p, const std::string& label) {
    GpuPrimitive g;
    g.vertices = gl::Buffer(label + " vertices");
    g.vertices.storage(p.vertices.size() * sizeof(MeshVertex), p.vertices.data(), 0);
    g.indices = gl::Buffer(label + " indices");
    g.indices.storage(p.indices.size() * sizeof(std::uint32_t), p.indices.data(), 0);
    const gl::VertexAttribute attributes[] = {{MESH_ATTRIBUTE_POSITION, 3, offsetof(MeshVertex, position)},
                                              {MESH_ATTRIBUTE_NORMAL, 3, offsetof(MeshVertex, normal)},
                                              {MESH_ATTRIBUTE_UV, 2, offsetof(MeshVertex, uv)}};
    g.vao = gl::vertex_array(g.vertices, sizeof(MeshVertex), g.indices, attributes, label);
    g.index_count = static_cast<GLsizei>(p.indices.size());
    g.material = p.material;
    g.transform = p.transform;
    return g;
}

// Base colour texels are sRGB-encoded: the sRGB format makes sampling return linear values.
gl::Texture upload_image(const MeshImage& image, const std::string& label) {
    return gl::srgb_texture(image.width, image.height, image.rgba.data(), label);
}

struct Lighting {
    glm::vec3 ambient{0.0f};
    std::vector<glm::vec3> directions, colors;
};

// The scene's lights; a scene without any gets a soft default so that meshes stay readable.
Lighting gather_lights(const Scene& scene) {
    Lighting l;
    const auto lights = scene.components<LightComponent>();
    for (const auto* light : lights) {
        const glm::vec3 radiance = light->color * light->intensity;
        if (light->kind == LightComponent::Kind::ambient) {
            l.ambient += radiance;
        } else if (l.directions.size() < MESH_MAX_DIRECTIONAL_LIGHTS) {
            const glm::vec3 dir = glm::vec3(light->node()->world_matrix() * glm::vec4(0, 0, -1, 0));
            l.directions.push_back(glm::normalize(dir));
            l.colors.push_back(radiance);
        }
    }
    if (lights.empty()) {
        l.ambient = glm::vec3(0.25f);
        l.directions.push_back(glm::normalize(glm::vec3(-0.4f, -1.0f, -0.6f)));
        l.colors.push_back(glm::vec3(0.9f));
    }
    return l;
}

}  // namespace

MeshPass::MeshPass(MeshStage stage) : stage_(stage) {}
MeshPass::~MeshPass() = default;

const gl::Texture& MeshPass::surface_depth(const RenderTarget& target) {
    const glm::ivec2 size(target.width(), target.height());
    if (!surface_depth_ || surface_depth_size_ != size) {
        surface_depth_ =
            std::make_unique<gl::Texture>(gl::texture_2d(GL_R32F, size.x, size.y, "late mesh surface depth"));
        surface_depth_size_ = size;
    }
    gl::copy_texture(target.view_depth(), *surface_depth_, size.x, size.y);
    return *surface_depth_;
}

const GpuMesh& MeshPass::gpu_mesh(const std::shared_ptr<const MeshAsset>& asset) {
    auto it = meshes_.find(asset.get());
    if (it != meshes_.end() && !it->second.first.expired()) return *it->second.second;
    auto gpu = std::make_unique<GpuMesh>();
    const std::string label = asset->source.filename().string();
    for (std::size_t i = 0; i < asset->primitives.size(); ++i)
        gpu->primitives.push_back(upload_primitive(asset->primitives[i], label + " #" + std::to_string(i)));
    for (const auto& image : asset->images) gpu->textures.push_back(upload_image(image, label + " " + image.name));
    auto& slot = meshes_[asset.get()];
    slot = {asset, std::move(gpu)};
    return *slot.second;
}

PickResult MeshPass::pick_answer(std::uint64_t ticket, bool) {
    return {true, answers_.find(ticket)};
}

void MeshPass::execute(FrameContext& frame) {
    std::erase_if(meshes_, [](const auto& entry) { return entry.second.first.expired(); });
    const bool late = stage_ == MeshStage::late;
    for (const PickRequest& request : frame.picks)
        answers_.add(request.ticket, pick_meshes(frame.scene, frame.camera, request.pixel, late));
    std::vector<const MeshComponent*> components;
    for (const auto* component : frame.scene.components<MeshComponent>())
        if (component->mesh && component->late == late) components.push_back(component);
    if (components.empty()) return;
    if (late) {
        const gl::TextureBinding surfaces[] = {{MESH_SURFACE_DEPTH_TEXTURE_UNIT, &surface_depth(frame.target)}};
        gl::bind({{}, {}, surfaces});
    }
    const auto& program =
        frame.shaders.program({"engine/mesh.vert.glsl", "engine/mesh.frag.glsl"},
                              late ? std::vector<std::string>{"MESH_LATE"} : std::vector<std::string>{});
    const Lighting lights = gather_lights(frame.scene);
    gl::set_uniform(program, "u_view", frame.camera.view);
    gl::set_uniform(program, "u_projection", flip_y_for_target(frame.camera.projection));
    gl::set_uniform(program, "u_ambient", lights.ambient);
    gl::set_uniform(program, "u_light_count", static_cast<int>(lights.directions.size()));
    gl::set_uniform(program, "u_light_direction", std::span<const glm::vec3>(lights.directions));
    gl::set_uniform(program, "u_light_color", std::span<const glm::vec3>(lights.colors));
    const gl::Uniform u_model = gl::uniform(program, "u_model"), u_normal = gl::uniform(program, "u_normal_matrix"),
                      u_factor = gl::uniform(program, "u_base_color_factor"),
                      u_has_texture = gl::uniform(program, "u_has_base_color_texture");

    // The target's Y flip reverses winding (render_target.h): clockwise fronts.
    const gl::RasterScope raster(program, frame.target.framebuffer(), frame.target.width(), frame.target.height(),
                                 true);
    for (const auto* component : components) {
        const GpuMesh& gpu = gpu_mesh(component->mesh);
        const glm::mat4 node_world = component->node()->world_matrix();
        for (const auto& prim : gpu.primitives) {
            const glm::mat4 model = node_world * prim.transform;
            gl::set_uniform(u_model, model);
            gl::set_uniform(u_normal, glm::transpose(glm::inverse(glm::mat3(model))));
            glm::vec4 factor(1.0f);
            int image = -1;
            if (prim.material >= 0) {
                const auto& material = component->mesh->materials[static_cast<std::size_t>(prim.material)];
                factor = material.base_color_factor;
                image = material.base_color_image;
            }
            gl::set_uniform(u_factor, factor);
            gl::set_uniform(u_has_texture, image >= 0 ? 1 : 0);
            const gl::Texture* texture = image >= 0 ? &gpu.textures[static_cast<std::size_t>(image)] : nullptr;
            raster.draw_triangles(prim.vao, prim.index_count, texture, MESH_BASE_COLOR_TEXTURE_UNIT);
        }
    }
}

}  // namespace engine
