// glTF 2.0 (.gltf, .glb) with KHR_gaussian_splatting primitives: every splat primitive of every node
// of the default scene, with the node's world transform applied, as one cloud.
#include <tiny_gltf.h>

#include <limits>
#include <set>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "engine/assets/gltf_external_files.h"
#include "engine/core/file_io.h"
#include "gltf_splats.h"
#include "io_util.h"
#include "readers.h"
#include "splat_lod/core/splat_io.h"

namespace splat_lod {
namespace {

namespace fs = std::filesystem;

// Images are of no use to splats: they are not decoded.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

tinygltf::Model parse(std::span<const std::uint8_t> bytes, const std::string& name, const fs::path& folder) {
    if (bytes.empty()) io::fail_file(name, "the file is empty");
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) io::fail_file(name, "larger than 4 GiB");
    const engine::GltfExternalFiles files(folder);  // external buffers: only in the model's folder
    tinygltf::TinyGLTF loader;
    files.install(loader);
    loader.SetImageLoader(&skip_image, nullptr);
    tinygltf::Model model;
    std::string err, warn;
    const auto size = static_cast<unsigned int>(bytes.size());
    const bool binary = bytes.size() >= 4 && bytes[0] == 'g' && bytes[1] == 'l' && bytes[2] == 'T' && bytes[3] == 'F';
    const std::string base_dir = folder.string();
    const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), size, base_dir)
                           : loader.LoadASCIIFromString(&model, &err, &warn,
                                                        reinterpret_cast<const char*>(bytes.data()), size, base_dir);
    if (!ok) {
        std::string why = err.empty() ? warn : err;
        while (!why.empty() && (why.back() == '\n' || why.back() == ' ')) why.pop_back();
        io::fail_file(name, "cannot load glTF: " + (why.empty() ? std::string("unknown error") : why));
    }
    return model;
}

glm::dmat4 node_matrix(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data());
    glm::dmat4 m(1.0);
    if (node.translation.size() == 3)
        m[3] = glm::dvec4(node.translation[0], node.translation[1], node.translation[2], 1.0);
    if (node.rotation.size() == 4) {
        const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
        if (glm::length(q) > 0.0) m *= glm::mat4_cast(glm::normalize(q));
    }
    if (node.scale.size() == 3)
        m *= glm::dmat4(glm::dvec4(node.scale[0], 0, 0, 0), glm::dvec4(0, node.scale[1], 0, 0),
                        glm::dvec4(0, 0, node.scale[2], 0), glm::dvec4(0, 0, 0, 1));
    return m;
}

struct SceneWalker {
    const tinygltf::Model& model;
    const std::string& name;
    LoadReport& report;
    SplatCloud cloud;
    std::set<int> seen;
    std::size_t primitives = 0;

    void visit(int index, const glm::dmat4& parent) {
        if (index < 0 || static_cast<std::size_t>(index) >= model.nodes.size())
            io::fail_file(name, "node index out of range: " + std::to_string(index));
        if (!seen.insert(index).second)
            io::fail_file(name, "node " + std::to_string(index) + " appears twice in the hierarchy (a cycle?)");
        const auto& node = model.nodes[static_cast<std::size_t>(index)];
        const glm::dmat4 world = parent * node_matrix(node);
        if (node.mesh >= 0) add_mesh(node.mesh, world, index);
        for (int child : node.children) visit(child, world);
    }

    void add_mesh(int mesh_index, const glm::dmat4& world, int node_index) {
        if (static_cast<std::size_t>(mesh_index) >= model.meshes.size())
            io::fail_file(name, "mesh index out of range: " + std::to_string(mesh_index));
        const auto& mesh = model.meshes[static_cast<std::size_t>(mesh_index)];
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            const auto& primitive = mesh.primitives[p];
            if (!primitive.extensions.count(io::kGltfSplatExtension)) continue;
            const std::string label = "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(p);
            SplatCloud part = io::decode_splat_primitive(model, primitive, name, label, report);
            io::apply_node_transform(part, world, name, "node " + std::to_string(node_index) + " (" + label + ")",
                                     report);
            io::append_cloud(cloud, part);
            ++primitives;
        }
    }
};

SplatCloud read_gltf_impl(std::span<const std::uint8_t> bytes, const std::string& name, const fs::path& folder,
                          LoadReport* report) {
    const tinygltf::Model model = parse(bytes, name, folder);
    LoadReport local;
    local.format = "glTF KHR_gaussian_splatting";
    SceneWalker walker{model, name, local, {}, {}, 0};
    if (!model.scenes.empty()) {
        const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
        if (static_cast<std::size_t>(scene) >= model.scenes.size())
            io::fail_file(name, "default scene index out of range");
        for (int root : model.scenes[static_cast<std::size_t>(scene)].nodes) walker.visit(root, glm::dmat4(1.0));
    } else {
        std::set<int> children;
        for (const auto& node : model.nodes) children.insert(node.children.begin(), node.children.end());
        for (std::size_t i = 0; i < model.nodes.size(); ++i)
            if (!children.count(static_cast<int>(i))) walker.visit(static_cast<int>(i), glm::dmat4(1.0));
    }
    if (walker.primitives == 0) io::fail_file(name, "no KHR_gaussian_splatting primitive in the scene");
    local.gaussians_in_file = walker.cloud.size() + local.dropped();  // SPZ streams drop theirs early
    io::finish_load(walker.cloud, local, report, name);
    return std::move(walker.cloud);
}

}  // namespace

SplatCloud read_gltf_splats(std::span<const std::uint8_t> bytes, const std::string& name, LoadReport* report) {
    return read_gltf_impl(bytes, name, {}, report);
}

SplatCloud read_gltf_splats(const fs::path& path, LoadReport* report) {
    const auto bytes = engine::read_binary_file(path);
    std::error_code ec;
    const fs::path folder = fs::absolute(path, ec).parent_path().lexically_normal();
    if (ec) io::fail_file(path.string(), "cannot resolve its folder: " + ec.message());
    return read_gltf_impl(bytes, path.string(), folder, report);
}

}  // namespace splat_lod
