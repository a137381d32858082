#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <stb_image.h>
#include <tiny_gltf.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "engine/assets/gltf_external_files.h"
#include "engine/assets/mesh_asset.h"
#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "engine/core/log.h"

namespace engine {
namespace {

// Required extensions this loader implements (none change the geometry it reads).
// Gaussian-splat primitives are not the mesh pass's: it skips them (MeshAsset::splat_primitives) and a
// plugin may draw them beside the mesh (ComponentRegistry::add_companion), so a file that requires the
// splat extensions still loads its triangles.
constexpr const char* kSplatExtension = "KHR_gaussian_splatting";
constexpr const char* supported_required_extensions[] = {"KHR_materials_unlit", "KHR_texture_transform",
                                                         kSplatExtension, "KHR_gaussian_splatting_compression_spz_2"};

float decode(const std::uint8_t* p, int type, bool normalized) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return normalized ? static_cast<float>(*p) / 255.0f : static_cast<float>(*p);
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const auto v = static_cast<float>(static_cast<std::int8_t>(*p));
            return normalized ? std::max(v / 127.0f, -1.0f) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            std::uint16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? static_cast<float>(v) / 65535.0f : static_cast<float>(v);
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            std::int16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? std::max(static_cast<float>(v) / 32767.0f, -1.0f) : static_cast<float>(v);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            std::uint32_t v;
            std::memcpy(&v, p, 4);
            return static_cast<float>(v);
        }
        default: {  // float (view_span rejected unknown types)
            float v;
            std::memcpy(&v, p, 4);
            return v;
        }
    }
}

// Values beyond float range in the file's JSON (doubles) become inf when converted.
template <int N>
bool finite(const glm::vec<N, float>& v) {
    for (int i = 0; i < N; ++i)
        if (!std::isfinite(v[i])) return false;
    return true;
}
bool finite(const glm::mat4& m) {
    return finite(m[0]) && finite(m[1]) && finite(m[2]) && finite(m[3]);
}

struct Loader {
    const std::filesystem::path& path;
    const tinygltf::Model& model;
    MeshAsset& out;

    [[noreturn]] void error(const std::string& what) const { fail(path.string() + ": " + what); }

    // Reads `components` floats per element of an accessor, converting normalised integers,
    // with every offset checked against the buffer so that hostile files cannot read outside it.
    std::vector<float> read_floats(int accessor_index, int components, const std::string& what) const {
        const std::string where = what + " (accessor " + std::to_string(accessor_index) + ")";
        if (accessor_index < 0 || static_cast<std::size_t>(accessor_index) >= model.accessors.size())
            error(where + ": accessor index out of range");
        const auto& a = model.accessors[static_cast<std::size_t>(accessor_index)];
        const int have = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
        if (have != components)
            error(where + ": expected " + std::to_string(components) + " components, found " + std::to_string(have));
        // Without a buffer view the specification says all zeros (or sparse values, not supported),
        // in any count the file claims: nothing backs it, so it is refused rather than allocated.
        if (a.bufferView < 0) error(where + ": no buffer view (sparse or zero-filled accessors are not supported)");
        const auto [base, stride, size] = view_span(a, components, where);  // checks the count first
        std::vector<float> values(a.count * static_cast<std::size_t>(components), 0.0f);
        const auto& bytes = buffer_of(a).data;
        for (std::size_t i = 0; i < a.count; ++i)
            for (int c = 0; c < components; ++c)
                values[i * static_cast<std::size_t>(components) + static_cast<std::size_t>(c)] =
                    decode(bytes.data() + base + i * stride + static_cast<std::size_t>(c) * size, a.componentType,
                           a.normalized);
        return values;
    }

    std::vector<std::uint32_t> read_indices(int accessor_index) const {
        const std::string where = "indices (accessor " + std::to_string(accessor_index) + ")";
        if (static_cast<std::size_t>(accessor_index) >= model.accessors.size())
            error(where + ": accessor index out of range");
        const auto& a = model.accessors[static_cast<std::size_t>(accessor_index)];
        if (a.type != TINYGLTF_TYPE_SCALAR || a.bufferView < 0) error(where + ": must be scalar with a buffer view");
        const auto [base, stride, size] = view_span(a, 1, where);
        std::vector<std::uint32_t> indices(a.count);
        const auto& bytes = buffer_of(a).data;
        for (std::size_t i = 0; i < a.count; ++i) {
            const std::uint8_t* p = bytes.data() + base + i * stride;
            switch (a.componentType) {
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                    indices[i] = *p;
                    break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                    std::uint16_t v;
                    std::memcpy(&v, p, 2);
                    indices[i] = v;
                    break;
                }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
                    std::memcpy(&indices[i], p, 4);
                    break;
                default:
                    error(where + ": unsupported index component type " + std::to_string(a.componentType));
            }
        }
        return indices;
    }

    const tinygltf::Buffer& buffer_of(const tinygltf::Accessor& a) const {
        const auto& view = model.bufferViews[static_cast<std::size_t>(a.bufferView)];
        return model.buffers[static_cast<std::size_t>(view.buffer)];
    }

    struct Span {
        std::size_t base, stride, component_size;
    };
    Span view_span(const tinygltf::Accessor& a, int components, const std::string& where) const {
        if (static_cast<std::size_t>(a.bufferView) >= model.bufferViews.size())
            error(where + ": buffer view out of range");
        const auto& view = model.bufferViews[static_cast<std::size_t>(a.bufferView)];
        if (a.componentType == TINYGLTF_COMPONENT_TYPE_DOUBLE) error(where + ": double components are not supported");
        if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
            error(where + ": buffer out of range");
        const auto& buffer = model.buffers[static_cast<std::size_t>(view.buffer)];
        const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
        if (size <= 0) error(where + ": unknown component type " + std::to_string(a.componentType));
        const std::size_t element = static_cast<std::size_t>(size) * static_cast<std::size_t>(components);
        const std::size_t stride = view.byteStride != 0 ? view.byteStride : element;
        if (stride < element) error(where + ": byte stride smaller than an element");
        const std::size_t base = view.byteOffset + a.byteOffset;
        if (view.byteOffset > buffer.data.size() || view.byteLength > buffer.data.size() - view.byteOffset)
            error(where + ": buffer view exceeds its buffer (" + std::to_string(buffer.data.size()) +
                  " bytes; truncated file?)");
        if (a.count > 0) {
            const std::size_t last = a.byteOffset + (a.count - 1) * stride + element;
            if (a.count > std::numeric_limits<std::size_t>::max() / stride || last > view.byteLength)
                error(where + ": " + std::to_string(a.count) + " elements exceed the buffer view");
        }
        return {base, stride, static_cast<std::size_t>(size)};
    }

    glm::mat4 node_matrix(const tinygltf::Node& node) const {
        if (node.matrix.size() == 16) {
            glm::mat4 m;
            for (int i = 0; i < 16; ++i)
                glm::value_ptr(m)[i] = static_cast<float>(node.matrix[static_cast<std::size_t>(i)]);
            return m;
        }
        glm::mat4 m(1.0f);
        if (node.translation.size() == 3)
            m = glm::translate(m, glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
        if (node.rotation.size() == 4)
            m *= glm::mat4_cast(
                glm::normalize(glm::quat(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                                         static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2]))));
        if (node.scale.size() == 3) m = glm::scale(m, glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
        return m;
    }

    void add_primitive(const tinygltf::Primitive& p, const glm::mat4& transform, const std::string& mesh_name) {
        const std::string what = "mesh '" + mesh_name + "'";
        if (p.extensions.count(kSplatExtension) != 0) {
            ++out.splat_primitives;
            return;
        }
        if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != -1) {
            log_warning(path.string() + ": " + what + ": skipping a primitive with mode " + std::to_string(p.mode) +
                        " (only triangles are drawn)");
            return;
        }
        const auto pos_it = p.attributes.find("POSITION");
        if (pos_it == p.attributes.end()) error(what + ": primitive without POSITION");
        const auto positions = read_floats(pos_it->second, 3, what + " POSITION");
        const std::size_t n = positions.size() / 3;
        std::vector<float> normals, uvs;
        if (auto it = p.attributes.find("NORMAL"); it != p.attributes.end())
            normals = read_floats(it->second, 3, what + " NORMAL");
        if (auto it = p.attributes.find("TEXCOORD_0"); it != p.attributes.end())
            uvs = read_floats(it->second, 2, what + " TEXCOORD_0");
        if ((!normals.empty() && normals.size() != n * 3) || (!uvs.empty() && uvs.size() != n * 2))
            error(what + ": attribute counts differ from POSITION's " + std::to_string(n));

        MeshPrimitive prim;
        prim.transform = transform;
        prim.material = p.material;
        if (p.material >= static_cast<int>(model.materials.size())) error(what + ": material index out of range");
        prim.vertices.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            auto& v = prim.vertices[i];
            v.position = {positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]};
            if (!std::isfinite(v.position.x) || !std::isfinite(v.position.y) || !std::isfinite(v.position.z))
                error(what + ": non-finite vertex position at index " + std::to_string(i));
            v.normal =
                normals.empty() ? glm::vec3(0) : glm::vec3(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
            v.uv = uvs.empty() ? glm::vec2(0) : glm::vec2(uvs[2 * i], uvs[2 * i + 1]);
            if (!std::isfinite(v.normal.x) || !std::isfinite(v.normal.y) || !std::isfinite(v.normal.z))
                error(what + ": non-finite NORMAL at index " + std::to_string(i));
            if (!std::isfinite(v.uv.x) || !std::isfinite(v.uv.y))
                error(what + ": non-finite TEXCOORD_0 at index " + std::to_string(i));
        }
        if (p.indices >= 0) {
            prim.indices = read_indices(p.indices);
        } else {
            prim.indices.resize(n);
            for (std::size_t i = 0; i < n; ++i) prim.indices[i] = static_cast<std::uint32_t>(i);
        }
        prim.indices.resize(prim.indices.size() / 3 * 3);
        for (auto index : prim.indices)
            if (index >= n)
                error(what + ": index " + std::to_string(index) + " beyond " + std::to_string(n) + " vertices");
        if (normals.empty()) compute_normals(prim);
        out.primitives.push_back(std::move(prim));
    }

    // Area-weighted vertex normals for meshes that come without them, summed in double: products of
    // float coordinates overflow float long before they overflow double.
    static void compute_normals(MeshPrimitive& prim) {
        std::vector<glm::dvec3> sums(prim.vertices.size(), glm::dvec3(0.0));
        for (std::size_t t = 0; t + 2 < prim.indices.size(); t += 3) {
            const std::uint32_t ia = prim.indices[t], ib = prim.indices[t + 1], ic = prim.indices[t + 2];
            const glm::dvec3 a(prim.vertices[ia].position), b(prim.vertices[ib].position),
                c(prim.vertices[ic].position);
            const glm::dvec3 n = glm::cross(b - a, c - a);
            sums[ia] += n;
            sums[ib] += n;
            sums[ic] += n;
        }
        for (std::size_t i = 0; i < prim.vertices.size(); ++i) {
            const double len = glm::length(sums[i]);
            prim.vertices[i].normal = len > 0.0 ? glm::vec3(sums[i] / len) : glm::vec3(0, 1, 0);
        }
    }

    void visit(int node_index, const glm::mat4& parent, int depth) {
        if (node_index < 0 || static_cast<std::size_t>(node_index) >= model.nodes.size())
            error("node index out of range: " + std::to_string(node_index));
        if (depth > 256) error("node hierarchy deeper than 256 (a cycle?)");
        const auto& node = model.nodes[static_cast<std::size_t>(node_index)];
        const glm::mat4 world = parent * node_matrix(node);
        if (!finite(world))
            error("node " + std::to_string(node_index) + ": transform is not finite (values beyond float range?)");
        if (node.mesh >= 0) {
            if (static_cast<std::size_t>(node.mesh) >= model.meshes.size())
                error("mesh index out of range: " + std::to_string(node.mesh));
            const auto& mesh = model.meshes[static_cast<std::size_t>(node.mesh)];
            for (const auto& p : mesh.primitives)
                add_primitive(p, world, mesh.name.empty() ? std::to_string(node.mesh) : mesh.name);
        }
        for (int child : node.children) visit(child, world, depth + 1);
    }

    void read_materials() {
        for (const auto& m : model.materials) {
            MeshMaterial mat;
            mat.name = m.name;
            const auto& f = m.pbrMetallicRoughness.baseColorFactor;
            if (f.size() == 4) mat.base_color_factor = glm::vec4(f[0], f[1], f[2], f[3]);
            if (!finite(mat.base_color_factor))
                error("material '" + m.name + "': baseColorFactor is not finite (values beyond float range?)");
            mat.double_sided = m.doubleSided;
            const int texture = m.pbrMetallicRoughness.baseColorTexture.index;
            if (texture >= 0) {
                if (static_cast<std::size_t>(texture) >= model.textures.size())
                    error("material '" + m.name + "': texture index out of range");
                const int source = model.textures[static_cast<std::size_t>(texture)].source;
                if (source < 0 || static_cast<std::size_t>(source) >= model.images.size())
                    error("material '" + m.name + "': image index out of range");
                mat.base_color_image = source;
            }
            out.materials.push_back(mat);
        }
    }

    void read_images() {
        for (std::size_t i = 0; i < model.images.size(); ++i) {
            const auto& im = model.images[i];
            const std::string name =
                im.uri.empty() ? (im.name.empty() ? "image " + std::to_string(i) : im.name) : im.uri;
            if (im.image.empty() || im.width <= 0 || im.height <= 0)
                error("texture '" + name + "' could not be loaded (missing or not an image)");
            MeshImage image{name, im.width, im.height, {}};
            const std::size_t pixels = static_cast<std::size_t>(im.width) * static_cast<std::size_t>(im.height);
            if (im.bits != 8 || im.component < 1 || im.component > 4 ||
                im.image.size() != pixels * static_cast<std::size_t>(im.component))
                error("texture '" + name + "': unsupported pixel format (" + std::to_string(im.component) +
                      " channels, " + std::to_string(im.bits) + " bits)");
            image.rgba.resize(pixels * 4);
            for (std::size_t p = 0; p < pixels; ++p) {
                const std::uint8_t* src = &im.image[p * static_cast<std::size_t>(im.component)];
                std::uint8_t* dst = &image.rgba[p * 4];
                dst[0] = src[0];
                dst[1] = im.component >= 3 ? src[1] : src[0];
                dst[2] = im.component >= 3 ? src[2] : src[0];
                dst[3] = im.component == 4 ? src[3] : (im.component == 2 ? src[1] : 255);
            }
            out.images.push_back(std::move(image));
        }
    }
};

// Images go through tinygltf's stb decoder after size checks: stb allocates for the sizes an image
// claims (texels, PNG chunk lengths) before decoding it, so a few kilobytes could claim gigabytes.
// Real textures stay far below the texel bound (deflate expands at most 1032:1, so even a flat
// 4096x4096 PNG takes tens of kilobytes).
constexpr std::uint64_t kMaxPixelsPerByte = 2048;
constexpr std::uint64_t kAlwaysAllowedPixels = 1 << 20;

// The offset of the first PNG chunk whose length runs past the end of the data, or 0 when every
// chunk fits (or the data are not PNG). stb allocates for a chunk's claimed length before reading it.
std::size_t png_chunk_past_end(const unsigned char* bytes, std::size_t size) {
    constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (size < 8 || std::memcmp(bytes, kSignature, 8) != 0) return 0;
    std::size_t offset = 8;
    while (offset + 8 <= size) {
        const std::uint64_t length = static_cast<std::uint64_t>(bytes[offset]) << 24 | bytes[offset + 1] << 16 |
                                     bytes[offset + 2] << 8 | bytes[offset + 3];
        if (length + 12 > size - offset) return offset;  // length, type, data, CRC
        offset += static_cast<std::size_t>(length) + 12;
    }
    return 0;
}

bool load_image_checked(tinygltf::Image* image, const int index, std::string* err, std::string* warn, int req_width,
                        int req_height, const unsigned char* bytes, int size, void* user_data) {
    const std::size_t bad_chunk = size > 0 ? png_chunk_past_end(bytes, static_cast<std::size_t>(size)) : 0;
    if (bad_chunk != 0) {
        if (err)
            *err += "image " + std::to_string(index) + ": PNG chunk at offset " + std::to_string(bad_chunk) +
                    " runs past the image's " + std::to_string(size) + " bytes (truncated?)\n";
        return false;
    }
    int width = 0, height = 0, channels = 0;
    if (size > 0 && stbi_info_from_memory(bytes, size, &width, &height, &channels)) {
        const std::uint64_t pixels = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
        if (pixels > kAlwaysAllowedPixels + kMaxPixelsPerByte * static_cast<std::uint64_t>(size)) {
            if (err)
                *err += "image " + std::to_string(index) + " claims " + std::to_string(width) + "x" +
                        std::to_string(height) + " texels, implausible for " + std::to_string(size) + " bytes\n";
            return false;
        }
    }
    return tinygltf::LoadImageData(image, index, err, warn, req_width, req_height, bytes, size, user_data);
}

void check_required_extensions(const std::filesystem::path& path, const tinygltf::Model& model) {
    for (const auto& ext : model.extensionsRequired) {
        const bool ok = std::any_of(std::begin(supported_required_extensions), std::end(supported_required_extensions),
                                    [&](const char* s) { return ext == s; });
        if (!ok) fail(path.string() + ": unsupported required extension " + ext);
    }
}

}  // namespace

std::size_t MeshAsset::triangle_count() const {
    std::size_t n = 0;
    for (const auto& p : primitives) n += p.indices.size() / 3;
    return n;
}

MeshAsset load_gltf(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) fail(path.string() + ": file not found");
    const std::string ext = path.extension().string();
    if (ext != ".glb" && ext != ".gltf") fail(path.string() + ": not a glTF file (expected .gltf or .glb)");
    return load_gltf(read_binary_file(path), path);
}

MeshAsset load_gltf(std::span<const std::uint8_t> bytes, const std::filesystem::path& path) {
    const std::string ext = path.extension().string();
    if (ext != ".glb" && ext != ".gltf") fail(path.string() + ": not a glTF file (expected .gltf or .glb)");
    if (bytes.empty()) fail(path.string() + ": the file is empty");
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) fail(path.string() + ": larger than 4 GiB");
    std::error_code ec;
    const GltfExternalFiles files(std::filesystem::absolute(path, ec).parent_path().lexically_normal());
    if (ec) fail(path.string() + ": cannot resolve its folder: " + ec.message());
    tinygltf::TinyGLTF loader;
    files.install(loader);
    loader.SetImageLoader(&load_image_checked, nullptr);
    tinygltf::Model model;
    std::string err, warn;
    const auto size = static_cast<unsigned int>(bytes.size());
    const std::string base_dir = files.folder().string();
    const auto* text = reinterpret_cast<const char*>(bytes.data());
    const bool ok = ext == ".glb" ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), size, base_dir)
                                  : loader.LoadASCIIFromString(&model, &err, &warn, text, size, base_dir);
    // Check required extensions first: a Draco file fails here with the real reason.
    if (!model.extensionsRequired.empty()) check_required_extensions(path, model);
    if (!ok) {
        std::string why = err.empty() ? warn : err;
        while (!why.empty() && (why.back() == '\n' || why.back() == ' ')) why.pop_back();
        fail(path.string() + ": cannot load glTF: " + (why.empty() ? "unknown error" : why));
    }
    if (!warn.empty()) log_warning(path.string() + ": " + warn);

    MeshAsset asset;
    asset.source = path;
    Loader l{path, model, asset};
    l.read_images();
    l.read_materials();
    const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (!model.scenes.empty()) {
        if (static_cast<std::size_t>(scene) >= model.scenes.size())
            fail(path.string() + ": default scene index out of range");
        for (int root : model.scenes[static_cast<std::size_t>(scene)].nodes) l.visit(root, glm::mat4(1.0f), 0);
    } else {
        for (std::size_t i = 0; i < model.nodes.size(); ++i) l.visit(static_cast<int>(i), glm::mat4(1.0f), 0);
    }
    if (asset.primitives.empty() && asset.splat_primitives == 0)
        fail(path.string() + ": no triangle geometry in the default scene");
    if (asset.primitives.empty()) return asset;  // splats only: bounds stay zero

    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const auto& p : asset.primitives)
        for (const auto& v : p.vertices) {
            const glm::vec3 w = glm::vec3(p.transform * glm::vec4(v.position, 1.0f));
            lo = glm::min(lo, w);
            hi = glm::max(hi, w);
        }
    if (!finite(lo) || !finite(hi))
        fail(path.string() + ": the model's bounds are not finite (coordinates beyond float range)");
    asset.bounds_min = lo;
    asset.bounds_max = hi;
    return asset;
}

}  // namespace engine
