#include "engine/scene/node.h"

#include <algorithm>

#include "engine/scene/scene.h"

namespace engine {

glm::mat4 Transform::matrix() const {
    glm::mat4 m = glm::mat4_cast(rotation);
    m[0] *= scale.x;
    m[1] *= scale.y;
    m[2] *= scale.z;
    m[3] = glm::vec4(translation, 1.0f);
    return m;
}

glm::quat Transform::look_rotation(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up) {
    const glm::vec3 forward = glm::normalize(target - eye);
    glm::vec3 right = glm::cross(forward, up);
    if (glm::dot(right, right) < 1e-12f) right = glm::cross(forward, glm::vec3(1, 0, 0));
    if (glm::dot(right, right) < 1e-12f) right = glm::cross(forward, glm::vec3(0, 0, 1));
    right = glm::normalize(right);
    const glm::vec3 true_up = glm::cross(right, forward);
    glm::mat3 basis(right, true_up, -forward);  // columns: +X, +Y, +Z of the node
    return glm::normalize(glm::quat_cast(basis));
}

Node& Node::add_child(std::string name) {
    children_.push_back(std::make_unique<Node>(std::move(name)));
    children_.back()->parent_ = this;
    return *children_.back();
}

bool Node::remove_child(const Node& child) {
    const auto it = std::find_if(children_.begin(), children_.end(), [&](const auto& c) { return c.get() == &child; });
    if (it == children_.end()) return false;
    children_.erase(it);
    return true;
}

void Node::attach(std::unique_ptr<Component> component) {
    component->node_ = this;
    components_.push_back(std::move(component));
}

glm::mat4 Node::world_matrix() const {
    const glm::mat4 local = transform_.matrix();
    return parent_ ? parent_->world_matrix() * local : local;
}

void Node::visit(const std::function<void(const Node&)>& fn) const {
    fn(*this);
    for (const auto& child : children_) static_cast<const Node&>(*child).visit(fn);
}

void Node::visit(const std::function<void(Node&)>& fn) {
    fn(*this);
    for (const auto& child : children_) child->visit(fn);
}

Node* Scene::find_node(const std::string& name) {
    Node* found = nullptr;
    root_.visit([&](Node& n) {
        if (!found && n.name() == name) found = &n;
    });
    return found;
}

std::optional<Bounds> Scene::world_bounds() const {
    std::optional<Bounds> result;
    root_.visit([&](const Node& node) {
        const glm::mat4 world = node.world_matrix();
        for (const auto& component : node.components()) {
            const auto local = component->local_bounds();
            if (!local) continue;
            for (int corner = 0; corner < 8; ++corner) {
                const glm::vec3 p((corner & 1) ? local->max.x : local->min.x,
                                  (corner & 2) ? local->max.y : local->min.y,
                                  (corner & 4) ? local->max.z : local->min.z);
                const glm::vec3 w = glm::vec3(world * glm::vec4(p, 1.0f));
                if (!result) result = Bounds{w, w};
                result->min = glm::min(result->min, w);
                result->max = glm::max(result->max, w);
            }
        }
    });
    return result;
}

}  // namespace engine
