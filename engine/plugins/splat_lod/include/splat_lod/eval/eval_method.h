#pragma once
// A method of the evaluation: a name and how it sets up the splat pass before its frames.
// Later LOD modes and upscalers join the registry as further methods through this interface.
#include <functional>
#include <string>
#include <vector>

namespace splat_lod {
class SplatPass;
}

namespace splat_lod::eval {

struct Method {
    std::string name;
    std::string description;
    // Called on a pass whose settings were reset to their defaults.
    std::function<void(SplatPass&)> configure;
};

// Every method known: "baseline" (the renderer as is) and "baseline_mip" (with the 2D mip filter).
const std::vector<Method>& method_registry();
// The methods of a comma-separated list, in its order; throws naming an unknown or repeated one.
std::vector<Method> select_methods(const std::string& list);
// The reference renderer's setup (ALGORITHMS §6: the fine model with the baseline renderer).
const Method& reference_method();
// `full` with each Gaussian tinted by its LOD level (the pass's debug view), for the level picture.
const Method& level_colouring_method();

// "1,2,4" → {1, 2, 4}; throws naming `option` on anything but positive integers.
std::vector<int> parse_int_list(const std::string& text, const std::string& option);
// "a,b" → {"a", "b"}; throws naming `option` on an empty or repeated name.
std::vector<std::string> parse_name_list(const std::string& text, const std::string& option);

}  // namespace splat_lod::eval
