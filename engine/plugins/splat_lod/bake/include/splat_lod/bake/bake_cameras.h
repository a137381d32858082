#pragma once
// The cameras a bake measures coverage in and refines against. A user with the training output
// passes its INRIA cameras.json; without one, a generated set around the scene stands in for the
// views the scene will be seen from (objects: rings of views around them). The generated set is
// deliberately different from the evaluation's orbit, so evaluations see held-out views.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "splat_lod/core/camera_set.h"
#include "splat_lod/core/reference_renderer.h"

namespace splat_lod::bake {

// "auto" (= "rings:3x8"): `rings` elevations (−0.15, 0.2, 0.55 rad for 3; spread over −0.2…0.7
// otherwise) × `per_ring` azimuths offset from ring to ring, at 2.2× the robust radius, 50° field
// of view. Anything else is an evaluation camera spec (orbit:N, INRIA cameras.json, a camera path).
// Errors name the spec or file and the problem.
std::vector<eval::CameraPose> bake_camera_poses(const std::string& spec, const eval::SceneExtent& extent,
                                                const glm::vec3& up);

// The reference (double-precision) cameras of the poses at width × height.
std::vector<reference::ReferenceCamera> bake_cameras(const std::vector<eval::CameraPose>& poses, int width, int height);

}  // namespace splat_lod::bake
