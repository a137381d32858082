// Distance fog over the frame (engine/render/fog_pass.h).
#include "engine/render/fog_pass.h"

#include <cmath>

#include "engine/core/error.h"
#include "engine/gl/compute_step.h"
#include "engine/gl/draw.h"
#include "engine/gl/shader_library.h"
#include "engine/render/render_target.h"

namespace engine {

std::string check_fog(const FogSettings& s) {
    for (int k = 0; k < 3; ++k)
        if (!(s.colour[k] >= 0.0f && s.colour[k] <= 1.0f)) return "fog: the colour must be in [0, 1]";
    if (!(std::isfinite(s.density) && s.density >= 0.0f)) return "fog: the density must be a number >= 0 (per metre)";
    if (!(std::isfinite(s.start_m) && s.start_m >= 0.0f)) return "fog: the start must be a number >= 0 (metres)";
    return {};
}

void FogPass::execute(FrameContext& frame) {
    if (!settings.enabled) return;
    if (const std::string problem = check_fog(settings); !problem.empty()) fail(problem);
    const gl::Program& program = frame.shaders.program({"engine/fog.comp.glsl"});
    gl::set_uniform(program, "u_fog", settings.colour);
    gl::set_uniform(program, "u_density", settings.density);
    gl::set_uniform(program, "u_start", settings.start_m);
    const gl::ImageBinding images[] = {{0, &frame.target.color(), GL_RGBA8}};
    const gl::TextureBinding textures[] = {{1, &frame.target.view_depth()}};
    gl::bind({{}, images, textures});
    const auto width = static_cast<std::uint32_t>(frame.target.width());
    const auto height = static_cast<std::uint32_t>(frame.target.height());
    gl::run({.program = &program,
             .groups = {gl::groups_for(width, 8), gl::groups_for(height, 8), 1},
             .barrier = GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT |
                        GL_TEXTURE_UPDATE_BARRIER_BIT});
    gl::end_steps();
}

}  // namespace engine
