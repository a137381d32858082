#include "splat_lod/eval/eval_report.h"

#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

#include "engine/core/error.h"
#include "engine/core/file_io.h"

namespace splat_lod::eval {
namespace {

std::string fixed(double value, int digits) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", digits, value);
    return buffer;
}

std::string csv_number(const std::optional<double>& value, int digits) {
    if (!value) return "";
    if (std::isinf(*value)) return *value > 0 ? "inf" : "-inf";
    return fixed(*value, digits);
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
        << csv_number(row.ssim, 6) << ',' << fixed(row.wall_ms, 3);
    for (const auto& name : spans) {
        const auto it = row.gpu_ms.find(name);
        out << ',' << (it == row.gpu_ms.end() ? std::string() : fixed(it->second, 3));
    }
    out << ',' << s.considered << ',' << s.visible;
    for (auto level : s.per_level) out << ',' << level;
    out << ',' << s.tile_splat_pairs << ',' << s.resident_bytes << '\n';
    return out.str();
}

std::string scale_table(const EvalResults& results) {
    const auto& o = results.options;
    std::ostringstream out;
    out << "| method |";
    for (int k : o.scales) out << ' ' << k << "\u00d7 |";
    out << "\n|---|";
    for (std::size_t i = 0; i < o.scales.size(); ++i) out << "---|";
    out << '\n';
    for (const auto& method : o.methods) {
        out << "| " << method.name << " |";
        for (int k : o.scales) {
            const Summary s = summarize(results, Sweep::scale, method.name, k);
            out << ' ' << format_db(s.psnr) << " / " << (s.ssim ? fixed(*s.ssim, 3) : "\u2013") << " / "
                << fixed(s.splat_gpu_ms, 2) << " |";
        }
        out << '\n';
    }
    return out.str();
}

std::string work_table(const EvalResults& results, Sweep sweep, const std::vector<int>& factors) {
    std::ostringstream out;
    const char* unit = sweep == Sweep::scale ? "scale" : "distance";
    out << "| method | " << unit
        << " | size | wall ms | GPU splat ms | considered | drawn | tile-splat pairs | PSNR | SSIM |\n"
           "|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& method : results.options.methods)
        for (int f : factors) {
            const Summary s = summarize(results, sweep, method.name, f);
            const auto& o = results.options;
            const int w = sweep == Sweep::scale ? o.width / f : o.width, h = sweep == Sweep::scale ? o.height / f : o.height;
            out << "| " << method.name << " | " << f << "\u00d7 | " << w << "\u00d7" << h << " | " << fixed(s.wall_ms, 2)
                << " | " << fixed(s.splat_gpu_ms, 2) << " | " << fixed(s.considered, 0) << " | " << fixed(s.visible, 0)
                << " | " << fixed(s.tile_splat_pairs, 0) << " | " << format_db(s.psnr) << " | "
                << (s.ssim ? fixed(*s.ssim, 4) : "\u2013") << " |\n";
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
        << fixed(summarize(results, results.rows.front().sweep, results.rows.front().method, results.rows.front().factor)
                         .resident_bytes / (1 << 20), 1)
        << " MiB.\n";
    return out.str();
}

}  // namespace

std::string format_db(const std::optional<double>& value) {
    if (!value) return "\u2013";
    if (std::isinf(*value)) return "\u221e";
    return fixed(*value, 2);
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
        s.considered += static_cast<double>(row.statistics.considered);
        s.visible += static_cast<double>(row.statistics.visible);
        s.tile_splat_pairs += static_cast<double>(row.statistics.tile_splat_pairs);
        s.resident_bytes += static_cast<double>(row.statistics.resident_bytes);
    }
    if (s.views == 0) return s;
    const double n = s.views;
    if (all_scored) {
        s.psnr = psnr_sum / n;
        s.ssim = ssim_sum / n;
    }
    s.wall_ms /= n;
    s.splat_gpu_ms /= n;
    s.considered /= n;
    s.visible /= n;
    s.tile_splat_pairs /= n;
    s.resident_bytes /= n;
    return s;
}

void write_csv(const EvalResults& results, const std::filesystem::path& path) {
    const auto spans = span_names(results);
    std::string text = "scene,sweep,view,view_name,method,factor,width,height,psnr_db,ssim,wall_ms";
    for (const auto& name : spans) text += ",gpu_" + name + "_ms";
    text += ",considered,visible,level1,level2,level3,level4,tile_splat_pairs,resident_bytes\n";
    for (const auto& row : results.rows) text += csv_row(row, spans);
    engine::write_text_file_atomic(path, text);
}

void write_markdown_report(const EvalResults& results, const std::string& renderer, const std::filesystem::path& path) {
    if (results.rows.empty()) engine::fail("splat_lod::eval::write_markdown_report(): no measurements");
    const auto& o = results.options;
    std::ostringstream out;
    out << "## " << o.scene_name << "\n\n" << setup_text(results, renderer) << '\n';
    if (has_sweep(results, Sweep::scale)) {
        out << "### Scale sweep\n\nEach cell: PSNR (dB) / SSIM / GPU time of the splat pass (ms), against the baseline "
               "render at full resolution area-averaged to the scale (\u221e: identical to the reference).\n\n"
            << scale_table(results) << "\n![time vs error](time_vs_error.png)\n\n"
            << "![contact sheet](contact_sheet.png)\n\n*Contact sheet, first view: rows reference, "
            << "then each method; columns the scales; every tile shown at the same size (area average when shrinking, "
            << "nearest neighbour when enlarging).*\n\n" << work_table(results, Sweep::scale, o.scales) << '\n';
    }
    if (has_sweep(results, Sweep::distance)) {
        out << "### Distance sweep\n\nThe camera dollies out along its view ray (distance to the target \u00d7 d) at a "
               "fixed " << o.width << "\u00d7" << o.height << " output. Error is measured only up to d = "
            << results.max_reference_distance << ", where the reference (d\u00b7W \u00d7 d\u00b7H, area-averaged) fits in "
            << o.max_reference_side << " pixels per side; beyond that the profile is time and work only.\n\n"
            << "![time vs distance](time_vs_distance.png) ![Gaussians vs distance](gaussians_vs_distance.png)\n\n"
            << work_table(results, Sweep::distance, o.distances) << '\n';
    }
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
}

}  // namespace splat_lod::eval
