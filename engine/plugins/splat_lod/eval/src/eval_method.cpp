#include "splat_lod/eval/eval_method.h"

#include <algorithm>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "splat_lod/splat_renderer.h"

namespace splat_lod::eval {

const std::vector<Method>& method_registry() {
    static const std::vector<Method> methods = {
        {"baseline", "the baseline renderer, every Gaussian of the fine model (level 1)",
         [](plugin_msgs::LodSettings& lod, SplatPassSettings&) { lod.rule.mode = plugin_msgs::LodMode::baseline; }},
        {"baseline_mip", "the baseline renderer with the optional 2D mip filter",
         [](plugin_msgs::LodSettings& lod, SplatPassSettings&) {
             lod.rule.mode = plugin_msgs::LodMode::baseline;
             lod.mip_filter = true;
         }},
        // The LOD ablation modes (docs/algorithms.md §3); on a scene without baked levels they equal baseline.
        {"filter_small", "level 1 only, Gaussians too small for this view left out",
         [](plugin_msgs::LodSettings& lod, SplatPassSettings&) { lod.rule.mode = plugin_msgs::LodMode::filter_small; }},
        {"insert_large", "every level, no filtering",
         [](plugin_msgs::LodSettings& lod, SplatPassSettings&) { lod.rule.mode = plugin_msgs::LodMode::insert_large; }},
        {"full", "every level, selected by pixel coverage (the multi-scale method), smooth transitions",
         [](plugin_msgs::LodSettings& lod, SplatPassSettings&) { lod.rule.mode = plugin_msgs::LodMode::full; }},
        {"full_hard", "every level, selected by pixel coverage, each Gaussian switched on or off at once",
         [](plugin_msgs::LodSettings& lod, SplatPassSettings&) { lod.rule.mode = plugin_msgs::LodMode::full_hard; }},
    };
    return methods;
}

const Method& reference_method() {
    return method_registry().front();
}

const Method& truth_method() {
    static const Method method = stored_as(reference_method(), GpuStorage::full);
    return method;
}

const Method& level_colouring_method() {
    static const Method method{"full", "every level, selected by pixel coverage, each Gaussian tinted by its level",
                               [](plugin_msgs::LodSettings& lod, SplatPassSettings&) {
                                   lod.rule.mode = plugin_msgs::LodMode::full;
                                   lod.level_colouring = true;
                               }};
    return method;
}

const Method& find_method(const std::string& name, const std::string& option) {
    const auto& all = method_registry();
    const auto it = std::find_if(all.begin(), all.end(), [&](const Method& m) { return m.name == name; });
    if (it != all.end()) return *it;
    std::string known;
    for (const auto& m : all) known += (known.empty() ? "" : ", ") + m.name;
    engine::fail(option + ": unknown method \"" + name + "\" (known: " + known + ")");
}

const std::vector<UpscalerVariant>& upscaler_registry() {
    using plugin_msgs::Upscaler;
    static const std::vector<UpscalerVariant> variants = {
        {"spline", "Hermite spline patches from the analytic derivatives (gradient-aware upscaling)", Upscaler::spline,
         true},
        {"bicubic", "bicubic from the low-resolution values (Keys, a = \u22120.5)", Upscaler::bicubic, true},
        {"bilinear", "bilinear from the low-resolution values", Upscaler::bilinear, true},
        {"lanczos3", "Lanczos-3 from the low-resolution values", Upscaler::lanczos3, true},
        {"spline_plain", "the spline with the plain 0.3 px\u00b2 dilation at the low resolution", Upscaler::spline,
         false},
    };
    return variants;
}

std::vector<UpscalerVariant> select_upscalers(const std::string& list) {
    std::vector<UpscalerVariant> selected;
    for (const std::string& name : parse_name_list(list, "--upscalers")) {
        const auto& all = upscaler_registry();
        const auto it = std::find_if(all.begin(), all.end(), [&](const UpscalerVariant& v) { return v.name == name; });
        if (it == all.end()) {
            std::string known;
            for (const auto& v : all) known += (known.empty() ? "" : ", ") + v.name;
            engine::fail("--upscalers: unknown upscaler \"" + name + "\" (known: " + known + ")");
        }
        selected.push_back(*it);
    }
    return selected;
}

Method upscaled_method(const Method& mode, const UpscalerVariant& variant, int factor) {
    if (factor < 1)
        engine::fail(std::string("splat_lod::eval::upscaled_method(): factor ") + std::to_string(factor) + " < 1");
    const auto configure_mode = mode.configure;
    return {variant.name, variant.description + ", " + mode.name + " at 1/" + std::to_string(factor),
            [configure_mode, variant, factor](plugin_msgs::LodSettings& lod, SplatPassSettings& settings) {
                if (configure_mode) configure_mode(lod, settings);
                lod.render_scale = 1.0f / static_cast<float>(factor);
                lod.upscaler = variant.upscaler;
                settings.scaled_dilation = variant.scaled_dilation;
            }};
}

Method native_method(const Method& mode) {
    const auto configure_mode = mode.configure;
    return {"native", mode.name + " at render scale 1",
            [configure_mode](plugin_msgs::LodSettings& lod, SplatPassSettings& settings) {
                if (configure_mode) configure_mode(lod, settings);
                lod.render_scale = 1.0f;
            }};
}

Method stored_as(const Method& method, GpuStorage storage) {
    const auto configure_method = method.configure;
    return {method.name, method.description,
            [configure_method, storage](plugin_msgs::LodSettings& lod, SplatPassSettings& settings) {
                if (configure_method) configure_method(lod, settings);
                settings.gpu_storage = storage;
            }};
}

namespace {

// A number that fills `text` and lies in [lo, hi]; none otherwise.
std::optional<double> number_in(const std::string& text, double lo, double hi) {
    std::size_t used = 0;
    double value = 0.0;
    try {
        value = std::stod(text, &used);
    } catch (const std::exception&) {
        return std::nullopt;
    }
    if (used != text.size() || !(value >= lo && value <= hi)) return std::nullopt;
    return value;
}

// "full@B" or "full@B:PLACEMENT": `full` with a transition band of B octaves placed as PLACEMENT says
// (inside, before, centred, staggered or auto: LodRule::transition_placement; `before` when left out, and with
// `auto` B is both bands, transition_band and overlap_transition_band), to choose the band by
// measurement; none when `name` has another form. Throws naming the method when B or the placement is
// not one the settings accept.
std::optional<Method> banded_full(const std::string& name) {
    const std::string prefix = "full@";
    if (name.rfind(prefix, 0) != 0) return std::nullopt;
    const std::string text = name.substr(prefix.size());
    const std::size_t colon = text.find(':');
    const auto band = number_in(text.substr(0, colon), 0.0, plugin_msgs::LodRule::kMaxTransitionBand);
    plugin_msgs::TransitionPlacement placement = plugin_msgs::TransitionPlacement::before;
    bool placement_known = true;
    if (colon != std::string::npos) try {
            placement = plugin_msgs::detail::enum_from_json<plugin_msgs::TransitionPlacement>(
                plugin_msgs::kTransitionPlacementNames, nlohmann::json(text.substr(colon + 1)));
        } catch (const std::invalid_argument&) {
            placement_known = false;
        }
    if (!band || !placement_known)
        engine::fail("--methods: \"" + name +
                     "\": expected full@B or full@B:PLACEMENT with a transition band B in [0, 4] octaves and "
                     "PLACEMENT one of inside, before, centred, staggered, auto");
    return Method{name,
                  "every level, selected by pixel coverage, transition band " + text.substr(0, colon) +
                      " octaves placed " + std::string(plugin_msgs::to_string(placement)),
                  [b = *band, p = placement](plugin_msgs::LodSettings& lod, SplatPassSettings&) {
                      lod.rule.mode = plugin_msgs::LodMode::full;
                      lod.rule.transition_band = static_cast<float>(b);
                      lod.rule.overlap_transition_band = static_cast<float>(b);
                      lod.rule.transition_placement = p;
                  }};
}

}  // namespace

std::vector<Method> select_methods(const std::string& list) {
    std::vector<Method> selected;
    std::stringstream stream(list);
    std::string name;
    while (std::getline(stream, name, ',')) {
        const auto& all = method_registry();
        const auto it = std::find_if(all.begin(), all.end(), [&](const Method& m) { return m.name == name; });
        const std::optional<Method> banded = banded_full(name);
        if (it == all.end() && !banded) {
            std::string known;
            for (const auto& m : all) known += (known.empty() ? "" : ", ") + m.name;
            engine::fail("--methods: unknown method \"" + name + "\" (known: " + known + ", full@B, full@B:PLACEMENT)");
        }
        if (std::any_of(selected.begin(), selected.end(), [&](const Method& m) { return m.name == name; }))
            engine::fail("--methods: \"" + name + "\" is listed twice");
        selected.push_back(banded ? *banded : *it);
    }
    if (selected.empty()) engine::fail("--methods: no method given");
    return selected;
}

std::vector<int> parse_int_list(const std::string& text, const std::string& option) {
    std::vector<int> values;
    std::stringstream stream(text);
    std::string item;
    while (std::getline(stream, item, ',')) {
        std::size_t used = 0;
        long value = 0;
        try {
            value = std::stol(item, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != item.size() || value < 1 || value > (1 << 20))
            engine::fail(option + ": \"" + item + "\" is not a positive integer");
        values.push_back(static_cast<int>(value));
    }
    if (values.empty()) engine::fail(option + ": no value given");
    return values;
}

std::vector<std::string> parse_name_list(const std::string& text, const std::string& option) {
    std::vector<std::string> names;
    std::stringstream stream(text);
    std::string name;
    while (std::getline(stream, name, ',')) {
        if (name.empty()) engine::fail(option + ": an empty name in \"" + text + "\"");
        if (std::find(names.begin(), names.end(), name) != names.end())
            engine::fail(option + ": \"" + name + "\" is listed twice");
        names.push_back(name);
    }
    if (names.empty()) engine::fail(option + ": no name given");
    return names;
}

}  // namespace splat_lod::eval
