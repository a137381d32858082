#pragma once
// Parsing of the small value types command-line tools take ("X,Y,Z").
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

namespace engine {

// "1,2.5,-3" → vec3; throws engine::Error naming `option` and the text otherwise.
glm::vec3 parse_vec3(const std::string& text, const std::string& option);

// "12,34" → a pixel (two whole numbers, not negative); throws engine::Error naming `option` and the text
// otherwise.
glm::ivec2 parse_pixel(const std::string& text, const std::string& option);

// A whole number 0 … 2^64 − 1 (CLI11 wraps "-3" and 2^64 into a std::uint64_t without complaint);
// throws engine::Error naming `option` and the text otherwise.
std::uint64_t parse_u64(const std::string& text, const std::string& option);

}  // namespace engine
