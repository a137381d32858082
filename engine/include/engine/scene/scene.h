#pragma once
#include <filesystem>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "engine/scene/node.h"

namespace engine {

class Scene {
public:
    Scene() : root_("root") {}
    Node& root() { return root_; }
    const Node& root() const { return root_; }

    // Every component of type T in the scene, depth-first.
    template <class T>
    std::vector<T*> components() const {
        std::vector<T*> out;
        root_.visit([&](const Node& n) {
            for (const auto& c : n.components())
                if (auto* typed = dynamic_cast<T*>(c.get())) out.push_back(typed);
        });
        return out;
    }

    Node* find_node(const std::string& name);

    // World-space bounds of every component that has extent, or nullopt when none has.
    std::optional<Bounds> world_bounds() const;

    // Display-space (sRGB-encoded) background colour and the ambient light (linear).
    glm::vec3 background{0.05f, 0.06f, 0.08f};
    std::filesystem::path source_file;  // the scene file it was loaded from, if any

private:
    Node root_;
};

}  // namespace engine
