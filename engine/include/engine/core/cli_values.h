#pragma once
// Parsing of the small value types command-line tools take ("X,Y,Z").
#include <string>

#include <glm/glm.hpp>

namespace engine {

// "1,2.5,-3" → vec3; throws engine::Error naming `option` and the text otherwise.
glm::vec3 parse_vec3(const std::string& text, const std::string& option);

}  // namespace engine
