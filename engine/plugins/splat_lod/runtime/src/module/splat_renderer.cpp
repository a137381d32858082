// The public handle to the splat pass (splat_lod/splat_renderer.h).
#include "splat_lod/splat_renderer.h"

#include "engine/core/error.h"
#include "engine/render/renderer.h"
#include "passes/splat_pass.h"

namespace splat_lod {

SplatRenderer::SplatRenderer(engine::Renderer& renderer) : renderer_(&renderer), pass_(find_splat_pass(renderer)) {
    if (pass_ == nullptr) engine::fail("splat_lod: the plugin is not started in this renderer (no splat pass)");
}

SplatPassSettings& SplatRenderer::settings() {
    return pass_->settings;
}
const SplatPassSettings& SplatRenderer::settings() const {
    return pass_->settings;
}
const plugin_msgs::LodSettings& SplatRenderer::lod() const {
    return pass_->lod();
}

const std::optional<plugin_msgs::SplatStatistics>& SplatRenderer::latest_statistics() const {
    return pass_->latest_statistics();
}

void SplatRenderer::wait_for_statistics(engine::MessageBus& bus) {
    pass_->wait_for_statistics(bus);
}

std::uint32_t SplatRenderer::key_capacity() const {
    return pass_->key_capacity();
}

RasterFetch SplatRenderer::raster_fetch_in_use() const {
    return pass_->raster_fetch_in_use();
}

std::uint64_t SplatRenderer::pick(glm::ivec2 pixel) {
    return renderer_->pick(pixel);
}

engine::PickResult SplatRenderer::pick_result(std::uint64_t ticket, bool wait) const {
    return renderer_->pick_result(ticket, wait, pass_);
}

std::size_t SplatRenderer::picks_in_flight() const {
    return pass_->picks_in_flight();
}

const char* to_string(RasterFetch fetch) {
    switch (fetch) {
        case RasterFetch::texel:
            return "texel";
        case RasterFetch::shared:
            return "shared";
        case RasterFetch::automatic:
            break;
    }
    return "automatic";
}

SplatMemory SplatRenderer::memory() const {
    const gpu::GpuScene& scene = pass_->scene();
    SplatMemory m;
    m.live_gaussians = scene.live_gaussians();
    m.gaussian_count = scene.gaussian_count();
    m.pages_in_use = scene.pages_in_use();
    m.free_pages = scene.free_pages();
    m.page_bytes = scene.page_bytes();
    m.last_upload_bytes = scene.last_upload_bytes();
    m.sh_stride = scene.sh_stride();
    m.storage = scene.storage();
    m.scene_bytes = scene.resident_bytes();
    m.frame_bytes = pass_->frame_bytes();
    m.view_bytes = pass_->view_bytes();
    m.selection_runs = pass_->last_frame_counts().selection_runs;
    m.strips = pass_->last_frame_counts().strips;
    return m;
}

void SplatRenderer::reserve(std::uint64_t gaussians, int sh_degree) {
    pass_->scene().reserve(gaussians, sh_degree, settings().gpu_storage);
}

upscale::GradientImage SplatRenderer::read_low_res_image() const {
    return pass_->read_low_res_image();
}

std::vector<float> SplatRenderer::read_low_res_front_depth() const {
    return pass_->read_low_res_front_depth();
}

SplatDepth SplatRenderer::read_splat_depth() const {
    return pass_->read_splat_depth();
}

}  // namespace splat_lod
