#pragma once
// Distance fog, a post pass (pass_order::post): every pixel whose view depth z is finite (the meshes'
// surfaces, and those a plugin merged in, such as the splats': render_target.h) moves toward the fog
// colour by f = 1 − exp(−density · max(z − start_m, 0)), mixed in linear light; pixels where nothing
// is (the background) keep their colour, so a fog colour near the background's lets the far field
// fade into it. One compute dispatch over the frame: it reads the view depth and rewrites the colour.
#include <string>

#include <glm/glm.hpp>

#include "engine/render/render_pass.h"

namespace engine {

struct FogSettings {
    bool enabled = true;
    glm::vec3 colour{0.62f, 0.72f, 0.82f};  // display space (sRGB-encoded), like the target's colour
    float density = 0.002f;                 // per metre: half fog at ln 2 / density beyond the start (347 m)
    float start_m = 0.0f;                   // metres of clear air in front of the camera
};

// What is wrong with the settings (a colour outside [0, 1], a negative or non-finite density or start),
// empty when they can be used.
std::string check_fog(const FogSettings& settings);

class FogPass : public RenderPass {
public:
    explicit FogPass(const FogSettings& fog = {}) : settings(fog) {}
    std::string name() const override { return "fog"; }
    int order() const override { return pass_order::post; }
    // Throws engine::Error when the settings are invalid.
    void execute(FrameContext& frame) override;

    FogSettings settings;
};

}  // namespace engine
