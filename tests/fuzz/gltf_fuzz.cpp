// glTF 2.0 through the engine's loader (engine/assets/mesh_asset.h, load_gltf from bytes): inputs
// starting with the GLB magic "glTF" are read as model.glb, others as model.gltf, both placed in
// the harness's sandbox folder, where buffer.bin and texture.png exist for external URIs
// (fuzz_support.h). The loader only reads external files inside that folder.
// Contract: a MeshAsset with finite vertices, in-range indices and materials, finite transforms
// and bounds, RGBA8 images; or engine::Error naming the file and the element.
#include <cstring>

#include "engine/assets/mesh_asset.h"
#include "engine/core/error.h"
#include "fuzz_support.h"

namespace {

using engine_fuzz::finite;
using engine_fuzz::require;

void check_primitive(const engine::MeshAsset& asset, const engine::MeshPrimitive& p) {
    require(finite(p.transform), "primitive transforms are finite");
    require(p.indices.size() % 3 == 0, "indices form whole triangles");
    for (const auto index : p.indices) require(index < p.vertices.size(), "indices address vertices");
    for (const auto& v : p.vertices)
        require(finite(v.position) && finite(v.normal) && finite(v.uv), "vertex attributes are finite");
    require(p.material >= -1 && p.material < static_cast<int>(asset.materials.size()), "material index in range");
}

void check_asset(const engine::MeshAsset& asset) {
    require(!asset.primitives.empty(), "a loaded model has triangles");
    for (const auto& p : asset.primitives) check_primitive(asset, p);
    for (const auto& m : asset.materials) {
        require(finite(m.base_color_factor), "base colour factors are finite");
        require(m.base_color_image >= -1 && m.base_color_image < static_cast<int>(asset.images.size()),
                "base colour image index in range");
    }
    for (const auto& image : asset.images)
        require(
            image.width > 0 && image.height > 0 &&
                image.rgba.size() == 4 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height),
            "images are RGBA8 of their size");
    require(finite(asset.bounds_min) && finite(asset.bounds_max), "bounds are finite");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    engine_fuzz::quiet_engine_log();
    engine_fuzz::write_sandbox_assets();
    const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    const auto path = engine_fuzz::sandbox_dir() / (binary ? "model.glb" : "model.gltf");
    engine::MeshAsset asset;
    try {
        asset = engine::load_gltf(engine_fuzz::bytes_of(data, size), path);
    } catch (const engine::Error& e) {
        engine_fuzz::check_error_names(e, path.string());
        return 0;
    }
    check_asset(asset);
    return 0;
}
