// What every step of the splat frame shares: its bindings and programs (frame_steps.h).
#include "passes/frame_steps.h"

#include <array>
#include <vector>

#include "engine/gl/compute_step.h"
#include "engine/render/render_target.h"

namespace splat_lod {

void FrameSteps::bind_all() const {
    const FrameBuffers& b = buffers;
    const engine::gl::BufferBinding storage[] = {{SPLAT_UNIFORM_FRAME, &b.uniforms, GL_UNIFORM_BUFFER},
                                                 {SPLAT_BINDING_GAUSSIANS, &scene.gaussians()},
                                                 {SPLAT_BINDING_SH, &scene.sh()},
                                                 {SPLAT_BINDING_INSTANCES, &scene.instances()},
                                                 {SPLAT_BINDING_PROJECTED, &b.projected},
                                                 {SPLAT_BINDING_CLUSTERS, &scene.clusters()},
                                                 {SPLAT_BINDING_CLUSTER_LIST, &b.cluster_list},
                                                 {SPLAT_BINDING_CLUSTER_PAIRS, &b.cluster_pairs},
                                                 {SPLAT_BINDING_KEYS, &b.keys},
                                                 {SPLAT_BINDING_VALUES, &b.values},
                                                 {SPLAT_BINDING_TILE_RANGES, &b.tile_ranges},
                                                 {SPLAT_BINDING_STATS, &b.counters},
                                                 {SPLAT_BINDING_ARGS, &b.args},
                                                 {SPLAT_BINDING_BUDGET, &b.budget},
                                                 {SPLAT_BINDING_PAGE_CODECS, &scene.page_codecs()},
                                                 {SPLAT_BINDING_CLUSTER_SPLATS, &b.cluster_splats},
                                                 {SPLAT_BINDING_PICKS, &b.picks},
                                                 {SPLAT_BINDING_CLUSTER_ROWS, &b.cluster_rows}};
    std::vector<engine::gl::ImageBinding> images{{SPLAT_IMAGE_COLOR, &frame.target.color(), GL_RGBA8},
                                                 {SPLAT_IMAGE_VIEW_DEPTH, &frame.target.view_depth(), GL_R32F}};
    if (low.width > 0)
        images.insert(images.end(), {{SPLAT_IMAGE_LOW_VALUE + 0, &low.images[0], GL_RGBA32F},
                                     {SPLAT_IMAGE_LOW_VALUE + 1, &low.images[1], GL_RGBA32F},
                                     {SPLAT_IMAGE_LOW_VALUE + 2, &low.images[2], GL_RGBA32F},
                                     {SPLAT_IMAGE_LOW_VALUE + 3, &low.images[3], GL_RGBA32F},
                                     {SPLAT_IMAGE_LOW_FRONT, &low.front, GL_RGBA32F}});
    if (depth.width > 0) images.push_back({SPLAT_IMAGE_SPLAT_DEPTH, &depth.image, GL_RG32F});
    const engine::gl::TextureBinding textures[] = {{SPLAT_TEXTURE_VIEW_DEPTH, &frame.target.view_depth()}};
    engine::gl::bind({storage, images, textures});
}

const engine::gl::Program& FrameSteps::program(const char* file, const std::vector<std::string>& defines) const {
    return frame.shaders.program({std::string("splat_lod/") + file}, defines);
}

}  // namespace splat_lod
