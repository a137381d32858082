// The world's glTF meshes (world/world_meshes.h), built face by face and serialised by tinygltf.
#include "splat_lod/worldgen/world_meshes.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <string>
#include <utility>

#include <tiny_gltf.h>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "world_layout.h"

namespace splat_lod::world {
namespace {

// Triangles of one material; flat faces get their own vertices so that normals stay sharp.
struct Part {
    Part(std::string name, const glm::vec4& base_colour, bool two_sided = false)
        : material(std::move(name)), colour(base_colour), double_sided(two_sided) {}

    std::string material;
    glm::vec4 colour{1.0f};  // linear base colour factor
    bool double_sided = false;
    std::vector<glm::vec3> positions, normals;
    std::vector<std::uint32_t> indices;

    std::uint32_t vertex(const glm::vec3& p, const glm::vec3& n) {
        positions.push_back(p);
        normals.push_back(n);
        return static_cast<std::uint32_t>(positions.size() - 1);
    }
    // A planar quad a b c d (in order around it) facing `outward`; the winding follows it.
    void quad(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
              const glm::vec3& outward) {
        glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
        const bool flip = glm::dot(n, outward) < 0.0f;
        if (flip) n = -n;
        const std::uint32_t i[4] = {vertex(a, n), vertex(b, n), vertex(c, n), vertex(d, n)};
        const std::uint32_t order[2][6] = {{0, 1, 2, 0, 2, 3}, {0, 2, 1, 0, 3, 2}};
        for (const std::uint32_t k : order[flip ? 1 : 0]) indices.push_back(i[k]);
    }
    void triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& outward) {
        glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
        const bool flip = glm::dot(n, outward) < 0.0f;
        if (flip) n = -n;
        const std::uint32_t i[3] = {vertex(a, n), vertex(b, n), vertex(c, n)};
        indices.insert(indices.end(), {i[0], flip ? i[2] : i[1], flip ? i[1] : i[2]});
    }
    // An axis-aligned box, all six faces.
    void box(const glm::vec3& lo, const glm::vec3& hi) {
        for (int axis = 0; axis < 3; ++axis)
            for (const float side : {-1.0f, 1.0f}) {
                const int u = (axis + 1) % 3, v = (axis + 2) % 3;
                glm::vec3 corner[4];
                for (int k = 0; k < 4; ++k) {
                    corner[k][axis] = side < 0.0f ? lo[axis] : hi[axis];
                    corner[k][u] = (k == 1 || k == 2) ? hi[u] : lo[u];
                    corner[k][v] = (k >= 2) ? hi[v] : lo[v];
                }
                glm::vec3 outward(0.0f);
                outward[axis] = side;
                quad(corner[0], corner[1], corner[2], corner[3], outward);
            }
    }
};

template <typename T>
int append_view(tinygltf::Model& model, const std::vector<T>& values, int target) {
    auto& data = model.buffers[0].data;
    const std::size_t offset = data.size();
    data.resize(offset + values.size() * sizeof(T));
    std::memcpy(data.data() + offset, values.data(), values.size() * sizeof(T));
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = offset;
    view.byteLength = values.size() * sizeof(T);
    view.target = target;
    model.bufferViews.push_back(view);
    return static_cast<int>(model.bufferViews.size() - 1);
}

int append_accessor(tinygltf::Model& model, int view, int component, int type, std::size_t count) {
    tinygltf::Accessor accessor;
    accessor.bufferView = view;
    accessor.componentType = component;
    accessor.type = type;
    accessor.count = count;
    model.accessors.push_back(accessor);
    return static_cast<int>(model.accessors.size() - 1);
}

void add_part(tinygltf::Model& model, tinygltf::Mesh& mesh, const Part& part) {
    tinygltf::Material material;
    material.name = part.material;
    material.pbrMetallicRoughness.baseColorFactor = {part.colour.x, part.colour.y, part.colour.z, part.colour.w};
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 0.9;
    material.doubleSided = part.double_sided;
    model.materials.push_back(material);

    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.material = static_cast<int>(model.materials.size() - 1);
    const int positions = append_accessor(model, append_view(model, part.positions, TINYGLTF_TARGET_ARRAY_BUFFER),
                                          TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, part.positions.size());
    // glTF requires the bounds of POSITION.
    glm::vec3 lo(part.positions.front()), hi(part.positions.front());
    for (const glm::vec3& p : part.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    model.accessors[static_cast<std::size_t>(positions)].minValues = {lo.x, lo.y, lo.z};
    model.accessors[static_cast<std::size_t>(positions)].maxValues = {hi.x, hi.y, hi.z};
    primitive.attributes["POSITION"] = positions;
    primitive.attributes["NORMAL"] =
        append_accessor(model, append_view(model, part.normals, TINYGLTF_TARGET_ARRAY_BUFFER),
                        TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, part.normals.size());
    primitive.indices =
        append_accessor(model, append_view(model, part.indices, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                        TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, part.indices.size());
    mesh.primitives.push_back(primitive);
}

// One mesh of `parts` under one node, as .glb bytes written atomically; returns the byte count.
std::uint64_t write_glb(const std::filesystem::path& path, const std::string& name, const std::vector<Part>& parts) {
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "splat_lod world generator";
    model.buffers.resize(1);
    tinygltf::Mesh mesh;
    mesh.name = name;
    for (const Part& part : parts)
        if (!part.indices.empty()) add_part(model, mesh, part);
    model.meshes.push_back(mesh);
    tinygltf::Node node;
    node.name = name;
    node.mesh = 0;
    model.nodes.push_back(node);
    tinygltf::Scene scene;
    scene.nodes = {0};
    model.scenes.push_back(scene);
    model.defaultScene = 0;

    std::ostringstream out;
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model, out, false, true))
        engine::fail(path.string() + ": tinygltf could not serialise the mesh");
    const std::string bytes = out.str();
    engine::write_text_file_atomic(path, bytes);
    return bytes.size();
}

std::vector<Part> house_parts() {
    Part walls{"walls", {0.62f, 0.55f, 0.42f, 1.0f}};
    Part roof{"roof", {0.33f, 0.07f, 0.04f, 1.0f}, true};
    Part trim{"door and windows", {0.06f, 0.07f, 0.09f, 1.0f}};
    Part chimney{"chimney", {0.28f, 0.10f, 0.07f, 1.0f}};
    // 6 m × 5 m, walls 3 m high, a gable roof along x with its ridge at 4.6 m and 0.3 m eaves.
    walls.box({-3.0f, 0.0f, -2.5f}, {3.0f, 3.0f, 2.5f});
    for (const float x : {-3.0f, 3.0f})
        walls.triangle({x, 3.0f, -2.5f}, {x, 3.0f, 2.5f}, {x, 4.45f, 0.0f}, {x, 0.0f, 0.0f});
    for (const float z : {-2.8f, 2.8f})
        roof.quad({-3.3f, 2.8f, z}, {3.3f, 2.8f, z}, {3.3f, 4.6f, 0.0f}, {-3.3f, 4.6f, 0.0f}, {0.0f, 1.0f, z});
    // Door and windows sit a centimetre proud of the front (+z) and back walls.
    trim.quad({-0.5f, 0.0f, 2.51f}, {0.5f, 0.0f, 2.51f}, {0.5f, 2.1f, 2.51f}, {-0.5f, 2.1f, 2.51f}, {0, 0, 1});
    for (const float z : {-2.51f, 2.51f})
        for (const float x : {-2.3f, 1.3f})
            trim.quad({x, 1.1f, z}, {x + 1.0f, 1.1f, z}, {x + 1.0f, 2.1f, z}, {x, 2.1f, z}, {0.0f, 0.0f, z});
    chimney.box({1.6f, 3.4f, -1.3f}, {2.1f, 5.2f, -0.8f});
    return {walls, roof, trim, chimney};
}

std::vector<Part> fence_parts() {
    // 2.5 m along x, centred: two posts and two rails (the layout stretches it along x to fit).
    Part wood{"wood", {0.30f, 0.19f, 0.10f, 1.0f}};
    for (const float x : {-1.2f, 1.2f}) wood.box({x - 0.05f, 0.0f, -0.05f}, {x + 0.05f, 1.1f, 0.05f});
    for (const float y : {0.40f, 0.85f}) wood.box({-1.25f, y, -0.02f}, {1.25f, y + 0.08f, 0.02f});
    return {wood};
}

std::vector<Part> post_parts() {
    Part wood{"wood", {0.26f, 0.16f, 0.09f, 1.0f}};
    Part sign{"sign", {0.80f, 0.78f, 0.70f, 1.0f}};
    Part band{"band", {0.55f, 0.06f, 0.04f, 1.0f}};
    wood.box({-0.07f, 0.0f, -0.07f}, {0.07f, 1.3f, 0.07f});
    sign.box({-0.25f, 1.0f, 0.07f}, {0.25f, 1.25f, 0.10f});
    band.box({-0.075f, 0.85f, -0.075f}, {0.075f, 0.93f, 0.075f});
    return {wood, sign, band};
}

// The lowest ground within ±reach of (x, z) (a 3 × 3 sample): flat triangles between vertices set
// there stay under a curved ground instead of cutting through its hollows.
float lowest_near(const WorldTerrain& terrain, float x, float z, float reach) {
    float lowest = terrain.height(x, z);
    for (const float dx : {-reach, 0.0f, reach})
        for (const float dz : {-reach, 0.0f, reach}) lowest = std::min(lowest, terrain.height(x + dx, z + dz));
    return lowest;
}

}  // namespace

std::uint64_t write_prop_meshes(const std::filesystem::path& folder) {
    return write_glb(folder / kHouseMesh, "house", house_parts()) +
           write_glb(folder / kFenceMesh, "fence", fence_parts()) + write_glb(folder / kPostMesh, "post", post_parts());
}

std::uint64_t write_terrain_mesh(const std::filesystem::path& folder, const WorldTerrain& terrain) {
    // Cells of 1/128 of the feature scale (at least 4 m): a larger world keeps the cell of its middle.
    const float size = terrain.size();
    const int cells =
        std::max(1, static_cast<int>(std::floor(size / std::max(4.0f, terrain.feature_scale() / 128.0f))));
    const float step = size / static_cast<float>(cells);
    Part ground{"ground", {0.16f, 0.20f, 0.08f, 1.0f}};
    for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i) {
            const float x = -0.5f * size + static_cast<float>(i) * step,
                        z = -0.5f * size + static_cast<float>(j) * step;
            ground.vertex({x, lowest_near(terrain, x, z, 0.5f * step) - 0.1f, z}, terrain.normal(x, z));
        }
    const auto at = [cells](int i, int j) { return static_cast<std::uint32_t>(j * (cells + 1) + i); };
    for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i)  // counter-clockwise seen from above (+y)
            ground.indices.insert(ground.indices.end(),
                                  {at(i, j), at(i, j + 1), at(i + 1, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)});
    return write_glb(folder / kTerrainMesh, "terrain", {ground});
}

}  // namespace splat_lod::world
