#include "engine/render/mesh_pass.h"

#include <engine/mesh_shared.h>  // shaders/engine/mesh_shared.h, shared with GLSL

#include <glm/gtc/type_ptr.hpp>

#include "engine/assets/mesh_asset.h"
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
    g.vao = gl::VertexArray(label);
    const GLuint vao = g.vao.id();
    glVertexArrayVertexBuffer(vao, 0, g.vertices.id(), 0, sizeof(MeshVertex));
    glVertexArrayElementBuffer(vao, g.indices.id());
    const struct {
        GLuint location;
        GLint size;
        GLuint offset;
    } attributes[] = {{MESH_ATTRIBUTE_POSITION, 3, offsetof(MeshVertex, position)},
                      {MESH_ATTRIBUTE_NORMAL, 3, offsetof(MeshVertex, normal)},
                      {MESH_ATTRIBUTE_UV, 2, offsetof(MeshVertex, uv)}};
    for (const auto& a : attributes) {
        glEnableVertexArrayAttrib(vao, a.location);
        glVertexArrayAttribFormat(vao, a.location, a.size, GL_FLOAT, GL_FALSE, a.offset);
        glVertexArrayAttribBinding(vao, a.location, 0);
    }
    g.index_count = static_cast<GLsizei>(p.indices.size());
    g.material = p.material;
    g.transform = p.transform;
    return g;
}

gl::Texture upload_image(const MeshImage& image, const std::string& label) {
    gl::Texture t(GL_TEXTURE_2D, label);
    int levels = 1;
    for (int s = std::max(image.width, image.height); s > 1; s /= 2) ++levels;
    // Base colour texels are sRGB-encoded: the sRGB format makes sampling return linear values.
    glTextureStorage2D(t.id(), levels, GL_SRGB8_ALPHA8, image.width, image.height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(t.id(), 0, 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
    glGenerateTextureMipmap(t.id());
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, GL_REPEAT);
    return t;
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

MeshPass::MeshPass() = default;
MeshPass::~MeshPass() = default;

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

void MeshPass::execute(FrameContext& frame) {
    std::erase_if(meshes_, [](const auto& entry) { return entry.second.first.expired(); });
    const auto& program = frame.shaders.program({"engine/mesh.vert.glsl", "engine/mesh.frag.glsl"});
    const GLuint p = program.id();
    const Lighting lights = gather_lights(frame.scene);
    glProgramUniformMatrix4fv(p, glGetUniformLocation(p, "u_view"), 1, GL_FALSE, glm::value_ptr(frame.camera.view));
    const glm::mat4 projection = flip_y_for_target(frame.camera.projection);
    glProgramUniformMatrix4fv(p, glGetUniformLocation(p, "u_projection"), 1, GL_FALSE, glm::value_ptr(projection));
    glProgramUniform3fv(p, glGetUniformLocation(p, "u_ambient"), 1, glm::value_ptr(lights.ambient));
    const auto light_count = static_cast<GLsizei>(lights.directions.size());
    glProgramUniform1i(p, glGetUniformLocation(p, "u_light_count"), light_count);
    if (light_count > 0) {
        glProgramUniform3fv(p, glGetUniformLocation(p, "u_light_direction"), light_count,
                            glm::value_ptr(lights.directions[0]));
        glProgramUniform3fv(p, glGetUniformLocation(p, "u_light_color"), light_count, glm::value_ptr(lights.colors[0]));
    }

    glBindFramebuffer(GL_FRAMEBUFFER, frame.target.framebuffer().id());
    glViewport(0, 0, frame.target.width(), frame.target.height());
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glFrontFace(GL_CW);  // the target's Y flip reverses winding (render_target.h)
    glUseProgram(p);
    const GLint model_loc = glGetUniformLocation(p, "u_model");
    const GLint normal_loc = glGetUniformLocation(p, "u_normal_matrix");
    const GLint factor_loc = glGetUniformLocation(p, "u_base_color_factor");
    const GLint has_tex_loc = glGetUniformLocation(p, "u_has_base_color_texture");

    for (const auto* component : frame.scene.components<MeshComponent>()) {
        if (!component->mesh) continue;
        const GpuMesh& gpu = gpu_mesh(component->mesh);
        const glm::mat4 node_world = component->node()->world_matrix();
        for (const auto& prim : gpu.primitives) {
            const glm::mat4 model = node_world * prim.transform;
            const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(model)));
            glUniformMatrix4fv(model_loc, 1, GL_FALSE, glm::value_ptr(model));
            glUniformMatrix3fv(normal_loc, 1, GL_FALSE, glm::value_ptr(normal_matrix));
            glm::vec4 factor(1.0f);
            int image = -1;
            if (prim.material >= 0) {
                const auto& material = component->mesh->materials[static_cast<std::size_t>(prim.material)];
                factor = material.base_color_factor;
                image = material.base_color_image;
            }
            glUniform4fv(factor_loc, 1, glm::value_ptr(factor));
            glUniform1i(has_tex_loc, image >= 0);
            if (image >= 0)
                glBindTextureUnit(MESH_BASE_COLOR_TEXTURE_UNIT, gpu.textures[static_cast<std::size_t>(image)].id());
            glBindVertexArray(prim.vao.id());
            glDrawElements(GL_TRIANGLES, prim.index_count, GL_UNSIGNED_INT, nullptr);
        }
    }
    glBindVertexArray(0);
    glUseProgram(0);
    glDisable(GL_DEPTH_TEST);
    glFrontFace(GL_CCW);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace engine
