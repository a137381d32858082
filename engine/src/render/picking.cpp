// Picking (engine/render/picking.h): the pixel's ray and the meshes' ray cast.
#include "engine/render/picking.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "engine/assets/mesh_asset.h"
#include "engine/core/error.h"
#include "engine/render/camera.h"
#include "engine/scene/builtin_components.h"
#include "engine/scene/node.h"
#include "engine/scene/scene.h"

namespace engine {
namespace {

struct Ray {
    glm::dvec3 origin, direction;  // world; direction scaled so that a step of 1 is a view depth of 1
};

Ray pixel_ray(const CameraView& camera, glm::ivec2 pixel) {
    const double f = camera.focal_length();
    const glm::dvec2 c = camera.principal_point();
    const glm::dvec3 view_direction((pixel.x + 0.5 - c.x) / f, -(pixel.y + 0.5 - c.y) / f, -1.0);
    const glm::dmat4 to_world = glm::inverse(glm::dmat4(camera.view));
    return {glm::dvec3(to_world[3]), glm::dmat3(to_world) * view_direction};
}

// Möller–Trumbore: the ray parameter of the hit of triangle (a, b, c), or +inf; both faces count.
double intersect(const Ray& ray, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const glm::dvec3 e1 = b - a, e2 = c - a;
    const glm::dvec3 p = glm::cross(ray.direction, e2);
    const double det = glm::dot(e1, p);
    const double inf = std::numeric_limits<double>::infinity();
    if (std::abs(det) < 1e-300) return inf;
    const glm::dvec3 s = ray.origin - a;
    const double u = glm::dot(s, p) / det;
    if (u < 0.0 || u > 1.0) return inf;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(ray.direction, q) / det;
    if (v < 0.0 || u + v > 1.0) return inf;
    return glm::dot(e2, q) / det;
}

// The nearest hit beyond `near` of one mesh component's triangles, transformed to the world.
double nearest_hit(const Ray& ray, const MeshComponent& mesh, double near) {
    double best = std::numeric_limits<double>::infinity();
    const glm::dmat4 node_world(mesh.node()->world_matrix());
    for (const MeshPrimitive& prim : mesh.mesh->primitives) {
        const glm::dmat4 model = node_world * glm::dmat4(prim.transform);
        const auto world = [&](std::uint32_t i) {
            return glm::dvec3(model * glm::dvec4(glm::dvec3(prim.vertices[i].position), 1.0));
        };
        for (std::size_t t = 0; t + 2 < prim.indices.size(); t += 3) {
            const double hit =
                intersect(ray, world(prim.indices[t]), world(prim.indices[t + 1]), world(prim.indices[t + 2]));
            if (hit > near && hit < best) best = hit;
        }
    }
    return best;
}

}  // namespace

glm::dvec3 pixel_ray_point(const CameraView& camera, glm::ivec2 pixel, double depth) {
    const Ray ray = pixel_ray(camera, pixel);
    return ray.origin + depth * ray.direction;
}

std::optional<PickHit> pick_meshes(const Scene& scene, const CameraView& camera, glm::ivec2 pixel, bool late) {
    const Ray ray = pixel_ray(camera, pixel);
    std::optional<PickHit> hit;
    for (const auto* mesh : scene.components<MeshComponent>()) {
        if (!mesh->mesh || mesh->late != late) continue;
        const double depth = nearest_hit(ray, *mesh, camera.znear);
        if (!std::isfinite(depth) || (hit && depth >= hit->depth)) continue;
        hit = PickHit{ray.origin + depth * ray.direction, depth, mesh->node(), mesh};
    }
    return hit;
}

void PickAnswers::add(std::uint64_t ticket, const std::optional<PickHit>& hit) {
    answers_[ticket] = hit;
    while (answers_.size() > kKept) {
        dropped_below_ = std::max(dropped_below_, answers_.begin()->first + 1);
        answers_.erase(answers_.begin());
    }
}

std::optional<PickHit> PickAnswers::find(std::uint64_t ticket) const {
    if (ticket < dropped_below_)
        fail("pick " + std::to_string(ticket) + ": its answer was dropped (only the newest " + std::to_string(kKept) +
             " are kept)");
    const auto it = answers_.find(ticket);
    return it != answers_.end() ? it->second : std::nullopt;
}

}  // namespace engine
