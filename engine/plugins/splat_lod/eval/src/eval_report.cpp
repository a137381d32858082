#include "splat_lod/eval/eval_report.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <sstream>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "splat_lod/eval/lod_report.h"
#include "splat_lod/eval/upscale_report.h"

namespace splat_lod::eval {
namespace {

std::string csv_number(const std::optional<double>& value, int digits) {
    if (!value) return "";
    if (std::isinf(*value)) return *value > 0 ? "inf" : "-inf";
    return format_fixed(*value, digits);
}

std::set<std::string> span_names(const EvalResults& results) {
    std::set<std::string> names;
    for (const auto& row : results.rows)
        for (const auto& [name, ms] : row.gpu_ms) names.insert(name);
    return names;
}

std::string csv_row(const Measurement& row, const std::set<std::string>& spans) {
    std::ostringstream out;
    const auto& s = row.statistics;
    out << row.scene << ',' << sweep_name(row.sweep) << ',' << row.view << ",\"" << row.view_name << "\"," << row.method
        << ',' << row.factor << ',' << row.width << ',' << row.height << ',' << csv_number(row.psnr, 4) << ','
        << csv_number(row.ssim, 6) << ',' << format_fixed(row.wall_ms, 3);
    for (const auto& name : spans) {
        const auto it = row.gpu_ms.find(name);
        out << ',' << (it == row.gpu_ms.end() ? std::string() : format_fixed(it->second, 3));
    }
    out << ',' << s.considered << ',' << s.skipped << ',' << s.visible;
    for (auto level : s.per_level) out << ',' << level;
    out << ',' << s.tile_splat_pairs << ',' << s.resident_bytes << '\n';
    return out.str();
}

// "| method | 1× | 4× | …" and its separator row.
std::string scale_header(const EvalOptions& o) {
    std::ostringstream out;
    out << "| method |";
    for (int k : o.scales) out << ' ' << k << "\u00d7 |";
    out << "\n|---|";
    for (std::size_t i = 0; i < o.scales.size(); ++i) out << "---|";
    out << '\n';
    return out.str();
}

std::string scale_table(const EvalResults& results) {
    const auto& o = results.options;
    std::ostringstream out;
    out << scale_header(o);
    for (const auto& method : measured_methods(o, Sweep::scale)) {
        out << "| " << method << " |";
        for (int k : o.scales) {
            const Summary s = summarize(results, Sweep::scale, method, k);
            out << ' ' << format_db(s.psnr) << " / " << (s.ssim ? format_fixed(*s.ssim, 3) : "\u2013") << " / "
                << format_fixed(s.splat_gpu_ms, 2) << " |";
        }
        out << '\n';
    }
    return out.str();
}

// The same grid with the mean Gaussians drawn per level: where the LOD methods trade level-1
// Gaussians for coarser ones.
std::string level_table(const EvalResults& results) {
    const auto& o = results.options;
    std::ostringstream out;
    out << scale_header(o);
    for (const auto& method : measured_methods(o, Sweep::scale)) {
        out << "| " << method << " |";
        for (int k : o.scales)
            out << ' ' << format_levels(summarize(results, Sweep::scale, method, k).per_level) << " |";
        out << '\n';
    }
    return out.str();
}

std::string work_table(const EvalResults& results, Sweep sweep, const std::vector<int>& factors) {
    std::ostringstream out;
    const char* unit = sweep == Sweep::scale ? "scale" : "distance";
    out << "| method | " << unit
        << " | size | wall ms | GPU splat ms | considered | drawn | drawn L1/L2/L3/L4 | tile-splat pairs | PSNR | SSIM "
           "|\n"
           "|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& method : measured_methods(results.options, sweep))
        for (int f : factors) {
            const Summary s = summarize(results, sweep, method, f);
            const auto& o = results.options;
            const int w = sweep == Sweep::scale ? o.width / f : o.width,
                      h = sweep == Sweep::scale ? o.height / f : o.height;
            out << "| " << method << " | " << f << "\u00d7 | " << w << "\u00d7" << h << " | "
                << format_fixed(s.wall_ms, 2) << " | " << format_fixed(s.splat_gpu_ms, 2) << " | "
                << format_fixed(s.considered, 0) << " | " << format_fixed(s.visible, 0) << " | "
                << format_levels(s.per_level) << " | " << format_fixed(s.tile_splat_pairs, 0) << " | "
                << format_db(s.psnr) << " | " << (s.ssim ? format_fixed(*s.ssim, 4) : "\u2013") << " |\n";
        }
    return out.str();
}

bool has_sweep(const EvalResults& results, Sweep sweep) {
    for (Sweep s : results.options.sweeps)
        if (s == sweep) return true;
    return false;
}

std::string setup_text(const EvalResults& results, const std::string& renderer) {
    const auto& o = results.options;
    std::ostringstream out;
    out << "Output " << o.width << "\u00d7" << o.height << ", " << results.views << " view(s), times are medians of "
        << o.frames << " frames after " << o.warmup << " warm-up frames (GPU: " << renderer
        << "; compare methods within one run). Values are means over the views. GPU memory resident for the scene: "
        << format_fixed(
               summarize(results, results.rows.front().sweep, results.rows.front().method, results.rows.front().factor)
                       .resident_bytes /
                   (1 << 20),
               1)
        << " MiB.\n";
    return out.str();
}

std::string comparison_list(const EvalOptions& o) {
    if (o.comparisons.empty()) return {};
    std::ostringstream out;
    out << "Comparison scenes, each drawn at the same views and scales and scored against the same reference:\n\n";
    for (const auto& comparison : o.comparisons)
        out << "- `" << comparison.method << "`: " << comparison.description << '\n';
    return out.str() + '\n';
}

std::string sheet_caption(const EvalOptions& o) {
    std::string rows;
    for (const auto& row : contact_sheet_rows(o)) rows += (rows.empty() ? "" : ", ") + row;
    return "*Contact sheet, first view: rows " + rows +
           "; columns the scales; every tile shown at the same size (area "
           "average when shrinking, nearest neighbour when enlarging).*\n\n";
}

// The storage sweep: the compact storage against the same method drawn from full floats, per method
// and distance, the worst view beside the mean (docs/gpu_storage.md: at least 45 dB wanted).
std::string storage_section(const EvalResults& results) {
    const auto& o = results.options;
    std::ostringstream out;
    out << "### Storage sweep\n\nEach method drawn from the compact GPU storage against the same method drawn "
           "from full floats, at the distances of the distance sweep (\u221e: identical).\n\n"
        << "| method | distance | PSNR, worst view | PSNR, mean | SSIM, mean | \u2265 45 dB "
           "|\n|---|---|---|---|---|---|\n";
    for (const Method& method : o.methods)
        for (int d : o.distances) {
            double worst = std::numeric_limits<double>::infinity();
            for (const Measurement& row : results.rows)
                if (row.sweep == Sweep::storage && row.method == method.name && row.factor == d && row.psnr)
                    worst = std::min(worst, *row.psnr);
            const Summary s = summarize(results, Sweep::storage, method.name, d);
            out << "| " << method.name << " | " << d << "\u00d7 | " << format_db(worst) << " | " << format_db(s.psnr)
                << " | " << (s.ssim ? format_fixed(*s.ssim, 4) : "\u2013") << " | "
                << (worst >= 45.0 ? "\u2713" : "\u2717") << " |\n";
        }
    return out.str() + '\n';
}

std::string scale_section(const EvalResults& results) {
    const auto& o = results.options;
    std::ostringstream out;
    out << "### Scale sweep\n\nEach cell: PSNR (dB) / SSIM / GPU time of the splat pass (ms), against the baseline "
           "render at full resolution area-averaged to the scale (\u221e: identical to the reference).\n\n"
        << scale_table(results)
        << "\nGaussians drawn per LOD level, L1/L2/L3/L4 (means over the views; k: thousands, M: millions):\n\n"
        << level_table(results) << '\n'
        << comparison_list(o);
    if (const auto verdict = lod_verdict(results)) out << lod_verdict_markdown(*verdict) << '\n';
    const auto matched = matched_counts(results);
    if (!matched.empty()) out << matched_counts_markdown(matched) << '\n';
    out << "![time vs error](time_vs_error.png)\n\n![contact sheet](contact_sheet.png)\n\n" << sheet_caption(o);
    if (!results.level_tiles.empty())
        out << "![levels](levels.png)\n\n*First view drawn by `full` with each Gaussian tinted by its level (L1 grey, "
               "L2 green, L3 blue, L4 red), at the contact sheet's tile size (nearest neighbour when enlarging).*\n\n";
    out << work_table(results, Sweep::scale, o.scales) << '\n';
    return out.str();
}

}  // namespace

std::vector<std::string> contact_sheet_rows(const EvalOptions& o) {
    std::vector<std::string> rows{"reference"};
    if (o.sheet_methods.empty())
        for (const auto& method : o.methods) rows.push_back(method.name);
    for (const auto& name : o.sheet_methods)
        if (name != "reference") rows.push_back(name);
    return rows;
}

std::string format_fixed(double value, int digits) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", digits, value);
    return buffer;
}

std::string format_count(double value) {
    if (value < 999.5) return format_fixed(value, 0);
    if (value < 999.95e3) return format_fixed(value / 1e3, 1) + "k";
    return format_fixed(value / 1e6, 2) + "M";
}

std::string format_levels(const std::array<double, 4>& per_level) {
    std::string text;
    for (double count : per_level) {
        if (!text.empty()) text += '/';  // (appended: GCC 12 warns falsely on "/" + std::string)
        text += format_count(count);
    }
    return text;
}

std::string format_db(const std::optional<double>& value) {
    if (!value) return "\u2013";
    if (std::isinf(*value)) return "\u221e";
    return format_fixed(*value, 2);
}

std::string format_signed_db(double value) {
    std::string text = value >= 0.0 ? "+" : "";
    text += format_fixed(value, 2);
    text += " dB";
    return text;
}

Summary summarize(const EvalResults& results, Sweep sweep, const std::string& method, int factor) {
    Summary s;
    double psnr_sum = 0.0, ssim_sum = 0.0;
    bool all_scored = true;
    for (const auto& row : results.rows) {
        if (row.sweep != sweep || row.method != method || row.factor != factor) continue;
        ++s.views;
        all_scored = all_scored && row.psnr && row.ssim;
        if (row.psnr) psnr_sum += *row.psnr;
        if (row.ssim) ssim_sum += *row.ssim;
        s.wall_ms += row.wall_ms;
        const auto it = row.gpu_ms.find("splat");
        s.splat_gpu_ms += it == row.gpu_ms.end() ? 0.0 : it->second;
        const auto upscale = row.gpu_ms.find("splat.upscale");
        s.upscale_gpu_ms += upscale == row.gpu_ms.end() ? 0.0 : upscale->second;
        s.considered += static_cast<double>(row.statistics.considered);
        s.visible += static_cast<double>(row.statistics.visible);
        s.tile_splat_pairs += static_cast<double>(row.statistics.tile_splat_pairs);
        s.resident_bytes += static_cast<double>(row.statistics.resident_bytes);
        for (std::size_t l = 0; l < s.per_level.size(); ++l)
            s.per_level[l] += static_cast<double>(row.statistics.per_level[l]);
    }
    if (s.views == 0) return s;
    const double n = s.views;
    if (all_scored) {
        s.psnr = psnr_sum / n;
        s.ssim = ssim_sum / n;
    }
    s.wall_ms /= n;
    s.splat_gpu_ms /= n;
    s.upscale_gpu_ms /= n;
    s.considered /= n;
    s.visible /= n;
    s.tile_splat_pairs /= n;
    s.resident_bytes /= n;
    for (double& count : s.per_level) count /= n;
    return s;
}

void write_csv(const EvalResults& results, const std::filesystem::path& path) {
    const auto spans = span_names(results);
    std::string text = "scene,sweep,view,view_name,method,factor,width,height,psnr_db,ssim,wall_ms";
    for (const auto& name : spans) text += ",gpu_" + name + "_ms";
    text += ",considered,skipped,visible,drawn_l1,drawn_l2,drawn_l3,drawn_l4,tile_splat_pairs,resident_bytes\n";
    for (const auto& row : results.rows) text += csv_row(row, spans);
    engine::write_text_file_atomic(path, text);
}

void write_markdown_report(const EvalResults& results, const std::string& renderer, const std::filesystem::path& path) {
    if (results.rows.empty()) engine::fail("splat_lod::eval::write_markdown_report(): no measurements");
    const auto& o = results.options;
    std::ostringstream out;
    out << "## " << o.scene_name << "\n\n" << setup_text(results, renderer) << '\n';
    if (has_sweep(results, Sweep::scale)) out << scale_section(results);
    if (has_sweep(results, Sweep::distance)) {
        out << "### Distance sweep\n\nThe camera dollies out along its view ray (distance to the target \u00d7 d) at a "
               "fixed "
            << o.width << "\u00d7" << o.height
            << " output. Error is measured only up to d = " << results.max_reference_distance
            << ", where the reference (d\u00b7W \u00d7 d\u00b7H, area-averaged) fits in " << o.max_reference_side
            << " pixels per side; beyond that the profile is time and work only.\n\n"
            << "![time vs distance](time_vs_distance.png) ![Gaussians vs distance](gaussians_vs_distance.png)\n\n"
            << work_table(results, Sweep::distance, o.distances) << '\n';
    }
    if (has_sweep(results, Sweep::upscale)) out << upscale_section(results);
    if (has_sweep(results, Sweep::storage)) out << storage_section(results);
    engine::write_text_file_atomic(path, out.str());
}

void write_outputs(const EvalResults& results, const std::string& renderer, const std::filesystem::path& folder) {
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (ec) engine::fail(folder.string() + ": cannot create the output folder: " + ec.message());
    write_csv(results, folder / "measurements.csv");
    write_markdown_report(results, renderer, folder / "report.md");
    write_plots(results, folder);
    if (has_sweep(results, Sweep::scale)) write_contact_sheet(results, folder / "contact_sheet.png");
    if (!results.level_tiles.empty()) write_level_picture(results, folder / "levels.png");
    if (has_sweep(results, Sweep::upscale)) write_upscale_crops(results, folder / "upscale_crops.png");
}

}  // namespace splat_lod::eval
