#pragma once
// A target a report checks (the LOD verdict, the upscale verdict): what is claimed, the measured
// value, and whether it holds.
#include <optional>
#include <string>

namespace splat_lod::eval {

struct Criterion {
    std::string text;             // "64×: full − baseline PSNR ≥ +3 dB"
    std::optional<double> value;  // absent: not measured
    std::string value_text;       // "+4.21 dB", "6.30×"
    bool met = false;
};

// ✓ met, ✗ not met, – not measured.
inline const char* criterion_mark(const Criterion& c) {
    if (!c.value) return "\u2013";
    return c.met ? "\u2713" : "\u2717";
}

// "- ✓ <text>: <value>\n" (a Markdown list item; "not measured" without a value).
inline std::string criterion_line(const Criterion& c) {
    return std::string("- ") + criterion_mark(c) + ' ' + c.text + ": " + (c.value ? c.value_text : "not measured") +
           '\n';
}

}  // namespace splat_lod::eval
