#include "splat_lod/eval/upscale_report.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "splat_lod/eval/eval_report.h"

namespace splat_lod::eval {
namespace {

bool upscale_timed(const EvalResults& results, const std::string& method, int factor) {
    bool any = false;
    for (const auto& row : results.rows)
        if (row.sweep == Sweep::upscale && row.method == method && row.factor == factor) {
            if (!row.gpu_ms.count("splat.upscale")) return false;
            any = true;
        }
    return any;
}

bool measured(const EvalResults& results, const std::string& method) {
    return std::any_of(results.rows.begin(), results.rows.end(),
                       [&](const Measurement& row) { return row.sweep == Sweep::upscale && row.method == method; });
}

UpscaleEntry make_entry(const EvalResults& results, const std::string& method, int factor, const Summary& native) {
    const auto& o = results.options;
    const Summary s = summarize(results, Sweep::upscale, method, factor);
    UpscaleEntry e;
    e.factor = factor;
    e.upscaler = method;
    e.source_width = upscale_source_side(o.width, factor);
    e.source_height = upscale_source_side(o.height, factor);
    e.psnr = s.psnr;
    e.ssim = s.ssim;
    e.render_ms = s.splat_gpu_ms - s.upscale_gpu_ms;
    e.upscale_ms = s.upscale_gpu_ms;
    e.frame_ms = s.wall_ms;
    if (native.wall_ms > 0.0 && s.wall_ms > 0.0) e.speedup_wall = native.wall_ms / s.wall_ms;
    if (native.splat_gpu_ms > 0.0 && s.splat_gpu_ms > 0.0) e.speedup_gpu = native.splat_gpu_ms / s.splat_gpu_ms;
    e.upscale_timed = upscale_timed(results, method, factor);
    return e;
}

std::string ratio(const std::optional<double>& value) {
    return value ? format_fixed(*value, 2) + "\u00d7" : "\u2013";
}

std::string signed_or_dash(const std::optional<double>& value) {
    return value ? format_signed_db(*value) : "\u2013";
}

std::optional<double> finite_difference(const std::optional<double>& a, const std::optional<double>& b) {
    if (!a || !b || !std::isfinite(*a) || !std::isfinite(*b)) return std::nullopt;
    return *a - *b;
}

const UpscaleVerdictRow* row_at(const UpscaleVerdict& verdict, int factor) {
    for (const auto& row : verdict.rows)
        if (row.factor == factor) return &row;
    return nullptr;
}

Criterion gain_criterion(const UpscaleVerdict& verdict, int factor) {
    Criterion c;
    c.text = std::to_string(factor) + "\u00d7: spline \u2212 bicubic PSNR \u2265 +" +
             format_fixed(kMinSplineGainDb, 0) + " dB";
    if (const UpscaleVerdictRow* row = row_at(verdict, factor); row && row->gain_over_bicubic_db) {
        c.value = row->gain_over_bicubic_db;
        c.value_text = format_signed_db(*c.value);
        c.met = *c.value >= kMinSplineGainDb;
    }
    return c;
}

Criterion fidelity_criterion(const UpscaleVerdict& verdict) {
    Criterion c;
    c.text = "3\u00d7: spline PSNR against native \u2265 " + format_fixed(kMinSplinePsnr3x, 0) + " dB";
    if (const UpscaleVerdictRow* row = row_at(verdict, 3); row && row->spline_psnr) {
        c.value = row->spline_psnr;
        c.value_text = format_db(c.value) + " dB";
        c.met = *c.value >= kMinSplinePsnr3x;
    }
    return c;
}

Criterion speed_criterion(const UpscaleVerdict& verdict) {
    const bool target_size = verdict.width == 1920 && verdict.height == 1080;
    Criterion c;
    c.text = "3\u00d7: spline frame speed-up over native \u2265 " + format_fixed(kMinSplineSpeedup3x, 1) + "\u00d7 (" +
             (target_size ? std::string("at 1920\u00d71080")
                          : std::string("a target at 1920\u00d71080; measured at ") + std::to_string(verdict.width) +
                                "\u00d7" + std::to_string(verdict.height)) +
             ")";
    if (const UpscaleVerdictRow* row = row_at(verdict, 3); row && row->speedup_wall) {
        c.value = row->speedup_wall;
        c.value_text = ratio(c.value);
        c.met = *c.value >= kMinSplineSpeedup3x;
    }
    return c;
}

std::string crops_caption(const EvalResults& results) {
    const engine::Image* native = nullptr;
    for (const auto& tile : results.upscale_tiles)
        if (tile.method == "native") native = &tile.image;
    if (!native) return {};
    const CropWindow w = detail_window(*native);
    std::string factors;
    for (int f : upscale_crop_factors(results.options))
        factors += std::string(factors.empty() ? "" : ", ") + std::to_string(f) + "\u00d7";
    std::string columns;
    for (const auto& c : upscale_crop_columns(results.options)) columns += (columns.empty() ? "" : ", ") + c;
    return std::string("![upscale crops](upscale_crops.png)\n\n*First view, the ") + std::to_string(w.width) +
           "\u00d7" + std::to_string(w.height) + " window at (" + std::to_string(w.x) + ", " + std::to_string(w.y) +
           ") with the most detail in the native image, magnified " + std::to_string(kCropMagnification) +
           "\u00d7 by nearest neighbour; columns " + columns + "; rows the factors " + factors +
           "; labels give each whole image's PSNR against native.*\n\n";
}

}  // namespace

std::vector<UpscaleEntry> upscale_entries(const EvalResults& results) {
    std::vector<UpscaleEntry> entries;
    if (!measured(results, "native")) return entries;
    const Summary native = summarize(results, Sweep::upscale, "native", 1);
    entries.push_back(make_entry(results, "native", 1, native));
    for (int f : results.options.upscale_factors)
        for (const auto& variant : results.options.upscalers)
            if (measured(results, variant.name)) entries.push_back(make_entry(results, variant.name, f, native));
    return entries;
}

std::string upscale_table_markdown(const std::vector<UpscaleEntry>& entries) {
    std::ostringstream out;
    out << "| factor | upscaler | raster size | PSNR (dB) | SSIM | render ms | upscale ms | frame ms | speed-up "
           "(frame) | speed-up (GPU) |\n|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& e : entries)
        out << "| " << e.factor << "\u00d7 | " << e.upscaler << " | " << e.source_width << "\u00d7" << e.source_height
            << " | " << format_db(e.psnr) << " | " << (e.ssim ? format_fixed(*e.ssim, 4) : "\u2013") << " | "
            << format_fixed(e.render_ms, 2) << " | " << (e.upscale_timed ? format_fixed(e.upscale_ms, 2) : "\u2013")
            << " | " << format_fixed(e.frame_ms, 2) << " | " << ratio(e.speedup_wall) << " | " << ratio(e.speedup_gpu)
            << " |\n";
    return out.str();
}

std::optional<UpscaleVerdict> upscale_verdict(const EvalResults& results) {
    if (!measured(results, "spline")) return std::nullopt;
    const auto& o = results.options;
    const Summary native = summarize(results, Sweep::upscale, "native", 1);
    UpscaleVerdict verdict;
    verdict.width = o.width;
    verdict.height = o.height;
    for (int f : o.upscale_factors) {
        const UpscaleEntry spline = make_entry(results, "spline", f, native);
        UpscaleVerdictRow row;
        row.factor = f;
        row.spline_psnr = spline.psnr;
        if (measured(results, "bicubic")) row.bicubic_psnr = summarize(results, Sweep::upscale, "bicubic", f).psnr;
        row.gain_over_bicubic_db = finite_difference(row.spline_psnr, row.bicubic_psnr);
        if (measured(results, "spline_plain"))
            row.gain_over_plain_db =
                finite_difference(row.spline_psnr, summarize(results, Sweep::upscale, "spline_plain", f).psnr);
        row.speedup_wall = spline.speedup_wall;
        row.speedup_gpu = spline.speedup_gpu;
        verdict.rows.push_back(row);
    }
    verdict.criteria = {gain_criterion(verdict, 2), gain_criterion(verdict, 3), gain_criterion(verdict, 4),
                        fidelity_criterion(verdict), speed_criterion(verdict)};
    return verdict;
}

std::string upscale_verdict_markdown(const UpscaleVerdict& verdict) {
    std::ostringstream out;
    out << "#### Upscale verdict: spline against bicubic and native\n\n"
           "| factor | spline PSNR (dB) | bicubic PSNR (dB) | spline \u2212 bicubic | spline \u2212 spline_plain | "
           "spline speed-up (frame) | spline speed-up (GPU) |\n|---|---|---|---|---|---|---|\n";
    for (const auto& row : verdict.rows)
        out << "| " << row.factor << "\u00d7 | " << format_db(row.spline_psnr) << " | " << format_db(row.bicubic_psnr)
            << " | " << signed_or_dash(row.gain_over_bicubic_db) << " | " << signed_or_dash(row.gain_over_plain_db)
            << " | " << ratio(row.speedup_wall) << " | " << ratio(row.speedup_gpu) << " |\n";
    out << '\n';
    for (const auto& c : verdict.criteria) out << criterion_line(c);
    return out.str();
}

std::string upscale_section(const EvalResults& results) {
    const std::vector<UpscaleEntry> entries = upscale_entries(results);
    if (entries.empty()) return {};
    const auto& o = results.options;
    std::ostringstream out;
    out << "### Upscale sweep\n\nThe splats are rasterised at 1/f of the " << o.width << "\u00d7" << o.height
        << " output (raster size \u2308W/f\u2309\u00d7\u2308H/f\u2309) and upscaled to it by each upscaler; LOD mode `"
        << o.upscale_mode
        << "`. Reference: the native render (render scale 1, same mode) at full size; `native` is a second native "
           "render scored against it (\u221e: deterministic). `spline_plain` is the spline without the "
           "resolution-consistent dilation (0.3 instead of 0.3/f\u00b2 low-res px\u00b2). render ms: GPU time of "
           "the splat pass without `splat.upscale`; upscale ms: `splat.upscale` (upscale and composite); frame ms: "
           "wall time of the whole frame; speed-up: native frame ms / frame ms, and native / this splat pass GPU "
           "ms.\n\n"
        << upscale_table_markdown(entries) << '\n';
    std::string untimed;
    for (const auto& e : entries)
        if (e.factor > 1 && !e.upscale_timed)
            untimed += std::string(untimed.empty() ? "" : ", ") + std::to_string(e.factor) + "\u00d7 " + e.upscaler;
    if (!untimed.empty())
        out << "**No `splat.upscale` GPU span was recorded** for " << untimed
            << ": the splat pass ran no upscale pass there, so those rows show the native render at the output "
               "size, not an upscaler.\n\n";
    if (const auto verdict = upscale_verdict(results)) out << upscale_verdict_markdown(*verdict) << '\n';
    out << crops_caption(results);
    return out.str();
}

}  // namespace splat_lod::eval
