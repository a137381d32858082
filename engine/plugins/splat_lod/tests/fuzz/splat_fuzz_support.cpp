#include "splat_fuzz_support.h"

#include <cmath>

#include "splat_lod/core/splat_io.h"

namespace splat_fuzz {
namespace {

splat_lod::SplatCloud small_cloud() {
    splat_lod::SplatCloud cloud;
    cloud.sh_degree = 1;
    cloud.resize(3);
    for (std::size_t i = 0; i < 3; ++i) {
        const float f = static_cast<float>(i);
        cloud.positions[i] = {f, 0.5f * f, -f};
        cloud.log_scales[i] = glm::vec3(-2.0f - 0.1f * f);
        cloud.opacity_logits[i] = 1.0f - f;
        cloud.sh_dc[i] = {0.1f * f, 0.2f, -0.3f};
        cloud.rotations[i] = {0.8f, 0.6f * (i == 1 ? 1.0f : 0.0f), 0.0f, 0.6f * (i == 1 ? 0.0f : 1.0f)};
    }
    for (std::size_t k = 0; k < cloud.sh_rest.size(); ++k) cloud.sh_rest[k] = 0.01f * static_cast<float>(k);
    return cloud;
}

}  // namespace

void check_cloud(const splat_lod::SplatCloud& cloud, const splat_lod::LoadReport& report) {
    cloud.check_consistent();  // throws engine::Error, a programming error here: make it a crash
    const std::size_t n = cloud.size();
    require(report.loaded == n, "report.loaded equals the cloud's size");
    require(report.gaussians_in_file == n + report.dropped(), "gaussians_in_file = loaded + dropped");
    const std::size_t stride = cloud.sh_rest_stride();
    for (std::size_t i = 0; i < n; ++i) {
        require(finite(cloud.positions[i]) && finite(cloud.log_scales[i]) && finite(cloud.sh_dc[i]) &&
                    std::isfinite(cloud.opacity_logits[i]),
                "Gaussian " + std::to_string(i) + " is finite");
        require(std::isfinite(cloud.coverage_min[i]) && std::isfinite(cloud.coverage_max[i]),
                "Gaussian " + std::to_string(i) + " has finite coverage bounds");
        const splat_lod::Rotation& r = cloud.rotations[i];
        const glm::vec4 q(r.w, r.x, r.y, r.z);
        require(finite(q) && std::fabs(glm::length(q) - 1.0f) < 1e-3f,
                "Gaussian " + std::to_string(i) + " has a unit quaternion");
        for (std::size_t k = 0; k < stride; ++k)
            require(std::isfinite(cloud.sh_rest[i * stride + k]), "Gaussian " + std::to_string(i) + " SH is finite");
        for (const auto& extra : cloud.extras)
            require(std::isfinite(extra.values[i]), "extra property " + extra.name + " is finite");
    }
}

void write_sandbox_assets() {
    static const bool written = [] {
        engine_fuzz::write_sandbox_assets();
        const splat_lod::SplatCloud cloud = small_cloud();
        write_file(sandbox_dir() / "cloud.ply", splat_lod::encode_inria_ply(cloud));
        write_file(sandbox_dir() / "cloud.splat", splat_lod::encode_antimatter_splat(cloud));
        return true;
    }();
    (void)written;
}

}  // namespace splat_fuzz
