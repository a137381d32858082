#include "engine/core/error.h"

namespace engine {

void fail(const std::string& message) {
    throw Error(message);
}

}  // namespace engine
