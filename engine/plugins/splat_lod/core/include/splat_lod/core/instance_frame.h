#pragma once
// Internal to the reference renderer: what project_gaussian needs per instance, computed once per
// instance rather than once per Gaussian.
#include <cstddef>

#include <glm/glm.hpp>

#include "splat_lod/core/reference_renderer.h"

namespace splat_lod::reference::detail {

struct InstanceFrame {
    glm::dmat4 model_view{1.0};          // W · model: local point → view space
    glm::dmat3 local_to_camera{1.0};     // diag(1, −1, −1) · W₃ · M: local offsets → image-aligned frame
    glm::dvec3 camera_local{0.0};        // the camera centre in the cloud's frame: model⁻¹ · c
    CullReason cull = CullReason::none;  // set when the model matrix itself is unusable
    int sh_degree = 0;
};

InstanceFrame make_instance_frame(const SplatCloud& cloud, const glm::dmat4& model, const ReferenceCamera& camera,
                                  const ReferenceSettings& settings, int sh_degree_cap);

ProjectedGaussian project_in_frame(const SplatCloud& cloud, std::size_t index, const InstanceFrame& frame,
                                   const ReferenceCamera& camera, const ReferenceSettings& settings);

// The activated opacity of a logit, in two branches so that neither exp() overflows (±60 and beyond).
double sigmoid(double logit);

// Throw engine::Error naming `caller` when the camera or the settings cannot be rendered with.
void check_camera(const ReferenceCamera& camera, const char* caller);
void check_settings(const ReferenceSettings& settings, const char* caller);

}  // namespace splat_lod::reference::detail
