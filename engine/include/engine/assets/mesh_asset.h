#pragma once
// A glTF model flattened for drawing: every triangle primitive of the default scene with the
// transform of its node, materials (base colour factor and texture) and decoded images.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace engine {

struct MeshVertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 uv;
};

struct MeshPrimitive {
    std::vector<MeshVertex> vertices;
    std::vector<std::uint32_t> indices;  // triangles
    int material = -1;                   // −1: the default material (white)
    glm::mat4 transform{1.0f};           // node → model root
};

struct MeshMaterial {
    std::string name;
    glm::vec4 base_color_factor{1.0f};  // linear
    int base_color_image = -1;          // index into MeshAsset::images, sRGB-encoded texels
    bool double_sided = false;
};

struct MeshImage {
    std::string name;
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;
};

struct MeshAsset {
    std::filesystem::path source;
    std::vector<MeshPrimitive> primitives;
    std::vector<MeshMaterial> materials;
    std::vector<MeshImage> images;
    glm::vec3 bounds_min{0.0f}, bounds_max{0.0f};  // model space, after node transforms
    // Primitives with KHR_gaussian_splatting: not drawn here, left to a plugin (a file may hold only these).
    std::size_t splat_primitives = 0;
    std::size_t triangle_count() const;
};

// Loads .gltf (external or embedded buffers) and .glb. Errors name the file and the element
// (e.g. "Box.gltf: unsupported required extension KHR_draco_mesh_compression"). External files
// (buffers, images) must be regular files in the model's folder or below it: a URI that is
// absolute or leaves the folder with ".." is an error, so a model cannot make us read elsewhere.
MeshAsset load_gltf(const std::filesystem::path& path);
// The same from the file's bytes; `path` names the model in messages, its extension (.gltf or
// .glb) says how to parse it and its folder is where external files are looked up.
MeshAsset load_gltf(std::span<const std::uint8_t> bytes, const std::filesystem::path& path);

}  // namespace engine
