#pragma once
#include <optional>
#include <string_view>

#include <glm/glm.hpp>

namespace engine {

class Node;

struct Bounds {
    glm::vec3 min{0.0f};
    glm::vec3 max{0.0f};
};

// Base of everything attached to a node. A type name identifies the component in scene files
// ("mesh", "camera", "light", and plugin types such as "splat").
class Component {
public:
    virtual ~Component() = default;
    virtual std::string_view type_name() const = 0;
    // Axis-aligned bounds in the node's local space, for components that have extent.
    virtual std::optional<Bounds> local_bounds() const { return std::nullopt; }

    Node* node() const { return node_; }

private:
    friend class Node;
    Node* node_ = nullptr;
};

}  // namespace engine
