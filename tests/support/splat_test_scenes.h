#pragma once
// Splat scenes for the gpu tier: the real captures in ../shared/data/splats, cameras that look at
// them, small synthetic clouds, and one-call GPU renders through the engine and the plugin.
#include <memory>
#include <string>
#include <vector>

#include "engine/engine.h"
#include "engine/render/camera.h"
#include "engine/render/image.h"
#include "splat_lod/core/splat_cloud.h"

namespace engine::test {

struct RealSplatScene {
    std::string name;
    std::filesystem::path path;
    glm::vec3 up;  // the capture's up direction (Y-down captures: (0, −1, 0))
};
std::vector<RealSplatScene> real_splat_scenes();

// Orbit cameras around the cloud's robust centre (median) at `distance_factor` × its robust radius
// (90th percentile distance), `count` views at different azimuths and elevations.
std::vector<CameraView> orbit_cameras(const splat_lod::SplatCloud& cloud, const glm::vec3& up, int count, int width,
                                      int height, float distance_factor = 2.2f);

// A cloud built in code: Gaussians with the given parameters (degree-0 SH from a linear colour).
struct GaussianSpec {
    glm::vec3 position{0.0f};
    glm::vec3 log_scale{-2.0f};
    glm::vec4 rotation{1, 0, 0, 0};  // w, x, y, z
    float opacity_logit = 2.0f;
    glm::vec3 color{0.5f};           // the colour SH degree 0 should give (before clamping)
};
splat_lod::SplatCloud make_cloud(const std::vector<GaussianSpec>& specs);

// Renders splat clouds (each under its own node with `models[i]`) through Engine + splat_lod,
// re-rendering while the key buffer had to grow, and returns the colour.
class SplatRenderHarness {
public:
    SplatRenderHarness();
    ~SplatRenderHarness();
    Image render(const std::vector<std::shared_ptr<const splat_lod::SplatCloud>>& clouds, const CameraView& camera,
                 const glm::vec3& background = glm::vec3(0.0f), const std::vector<glm::mat4>& models = {});
    Engine& engine() { return *engine_; }

private:
    std::unique_ptr<Engine> engine_;
};

}  // namespace engine::test
