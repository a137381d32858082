#include "engine/core/cli_values.h"

#include <charconv>
#include <cmath>
#include <sstream>

#include "engine/core/error.h"

namespace engine {

glm::vec3 parse_vec3(const std::string& text, const std::string& option) {
    glm::vec3 v;
    char c1 = 0, c2 = 0;
    std::istringstream in(text);
    if (!(in >> v.x >> c1 >> v.y >> c2 >> v.z) || c1 != ',' || c2 != ',' || !(in >> std::ws).eof() ||
        !std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        fail(option + ": expected three finite numbers X,Y,Z, got '" + text + "'");
    return v;
}

glm::ivec2 parse_pixel(const std::string& text, const std::string& option) {
    glm::ivec2 p(-1);
    char comma = 0;
    std::istringstream in(text);
    if (!(in >> p.x >> comma >> p.y) || comma != ',' || !(in >> std::ws).eof() || p.x < 0 || p.y < 0)
        fail(option + ": expected a pixel X,Y (two whole numbers, not negative), got '" + text + "'");
    return p;
}

std::uint64_t parse_u64(const std::string& text, const std::string& option) {
    std::uint64_t value = 0;
    const char* end = text.data() + text.size();
    const auto [stop, error] = std::from_chars(text.data(), end, value);
    if (text.empty() || error != std::errc() || stop != end)
        fail(option + " must be a whole number from 0 to 18446744073709551615, got \"" + text + "\"");
    return value;
}

}  // namespace engine
