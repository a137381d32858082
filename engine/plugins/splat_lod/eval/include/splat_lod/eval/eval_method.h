#pragma once
// A method of the evaluation: a name and how it sets up the splat pass before its frames.
// The LOD modes are in the registry; the upscale sweep builds its methods from a mode, an upscaler
// variant and a factor.
#include <functional>
#include <string>
#include <vector>

#include "splat_lod/gpu_storage.h"
#include "splat_lod/msgs/lod_settings.h"

namespace splat_lod {
struct SplatPassSettings;
}

namespace splat_lod::eval {

struct Method {
    std::string name;
    std::string description;
    // Called on the LOD settings (published on the bus afterwards) and the pass's technical settings,
    // both reset to their defaults.
    std::function<void(plugin_msgs::LodSettings&, SplatPassSettings&)> configure;
};

// Every method known: "baseline" (the renderer as is) and "baseline_mip" (with the 2D mip filter).
const std::vector<Method>& method_registry();
// The methods of a comma-separated list, in its order; throws naming an unknown or repeated one.
std::vector<Method> select_methods(const std::string& list);
// The reference renderer's setup (docs/algorithms.md §6: the fine model with the baseline renderer).
const Method& reference_method();
// The references' own frames: reference_method() drawn from full floats (docs/gpu_storage.md), so that
// what every method is scored against carries no storage error.
const Method& truth_method();
// `full` with each Gaussian tinted by its LOD level (the pass's debug view), for the level picture.
const Method& level_colouring_method();

// Finds a method of the registry by name; throws naming `option` and the known names otherwise.
const Method& find_method(const std::string& name, const std::string& option);

// How the upscale sweep brings a render at 1/f of the output to the output (docs/algorithms.md §5).
struct UpscalerVariant {
    std::string name;  // the method name its measurements carry: "spline", "spline_plain", ...
    std::string description;
    plugin_msgs::Upscaler upscaler = plugin_msgs::Upscaler::spline;
    bool scaled_dilation = true;  // false: the plain 0.3 low-res px² (blurrier than native)
};

// spline, bicubic, bilinear, lanczos3 (resolution-consistent dilation) and spline_plain (the
// spline with the plain dilation, to show what the consistent one buys).
const std::vector<UpscalerVariant>& upscaler_registry();
// The variants of a comma-separated list, in its order; throws naming an unknown or repeated one.
std::vector<UpscalerVariant> select_upscalers(const std::string& list);
// `mode` rendered at render scale 1/factor and brought to the output by `variant`.
Method upscaled_method(const Method& mode, const UpscalerVariant& variant, int factor);
// `mode` at render scale 1 under the name "native": the upscale sweep's reference and time base.
Method native_method(const Method& mode);

// `method` with the scene stored on the GPU as `storage` says (the storage sweep), under the same name.
Method stored_as(const Method& method, GpuStorage storage);

// "1,2,4" → {1, 2, 4}; throws naming `option` on anything but positive integers.
std::vector<int> parse_int_list(const std::string& text, const std::string& option);
// "a,b" → {"a", "b"}; throws naming `option` on an empty or repeated name.
std::vector<std::string> parse_name_list(const std::string& text, const std::string& option);

}  // namespace splat_lod::eval
