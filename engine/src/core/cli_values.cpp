#include "engine/core/cli_values.h"

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

}  // namespace engine
