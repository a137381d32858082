#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/scene/component.h"
#include "engine/scene/transform.h"

namespace engine {

class Node {
public:
    explicit Node(std::string name = {}) : name_(std::move(name)) {}
    Node(const Node&) = delete;
    Node& operator=(const Node&) = delete;

    const std::string& name() const { return name_; }
    Transform& transform() { return transform_; }
    const Transform& transform() const { return transform_; }
    Node* parent() const { return parent_; }

    Node& add_child(std::string name);
    // Destroys a direct child with its subtree and components; false when `child` is not one.
    // References to it (and to anything below it) dangle afterwards.
    bool remove_child(const Node& child);
    const std::vector<std::unique_ptr<Node>>& children() const { return children_; }

    template <class T>
    T& add_component(std::unique_ptr<T> component) {
        T& ref = *component;
        attach(std::move(component));
        return ref;
    }
    void attach(std::unique_ptr<Component> component);
    const std::vector<std::unique_ptr<Component>>& components() const { return components_; }

    template <class T>
    T* find_component() const {
        for (const auto& c : components_)
            if (auto* typed = dynamic_cast<T*>(c.get())) return typed;
        return nullptr;
    }

    // Parent chain applied: world = parent.world · local.
    glm::mat4 world_matrix() const;

    // Depth-first, parents before children.
    void visit(const std::function<void(const Node&)>& fn) const;
    void visit(const std::function<void(Node&)>& fn);

private:
    std::string name_;
    Transform transform_;
    Node* parent_ = nullptr;
    std::vector<std::unique_ptr<Node>> children_;
    std::vector<std::unique_ptr<Component>> components_;
};

}  // namespace engine
