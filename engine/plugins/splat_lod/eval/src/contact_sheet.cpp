// The contact sheet: one row per image source (the reference, then each method), one column per
// scale, every tile brought to the same display size so that the low scales show their pixels;
// and the level picture in the same layout.
#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "splat_lod/eval/eval_report.h"
#include "splat_lod/eval/sheet_drawing.h"

namespace splat_lod::eval {
namespace {

constexpr int kLabelWidth = 96;
constexpr int kGap = 2;

const engine::Image* find_tile(const std::vector<ContactTile>& tiles, const std::string& row, int scale) {
    for (const auto& tile : tiles)
        if (tile.method == row && tile.factor == scale) return &tile.image;
    return nullptr;
}

// Rows of labelled tiles under a header of scales, `extra_height` pixels left free at the bottom.
engine::Image compose(const EvalOptions& o, const std::vector<ContactTile>& tiles, const std::vector<std::string>& rows,
                      const std::vector<int>& scales, int extra_height) {
    const int tw = std::max(1, o.sheet_tile_width > 0 ? o.sheet_tile_width : o.width / 4);
    const int th = std::max(1, tw * o.height / o.width);
    const int columns = static_cast<int>(scales.size());
    engine::Image sheet = black_image(kLabelWidth + columns * (tw + kGap),
                                      kLabelHeight + static_cast<int>(rows.size()) * (th + kGap) + extra_height);
    for (int c = 0; c < columns; ++c)
        draw_text(sheet, kLabelWidth + c * (tw + kGap) + 4, 4,
                  std::to_string(scales[static_cast<std::size_t>(c)]) + "x");
    for (std::size_t r = 0; r < rows.size(); ++r) {
        const int y0 = kLabelHeight + static_cast<int>(r) * (th + kGap);
        draw_text(sheet, 4, y0 + th / 2 - 4, rows[r]);
        for (int c = 0; c < columns; ++c)
            if (const engine::Image* tile = find_tile(tiles, rows[r], scales[static_cast<std::size_t>(c)]))
                draw_scaled(sheet, *tile, kLabelWidth + c * (tw + kGap), y0, tw, th);
    }
    return sheet;
}

}  // namespace

void write_contact_sheet(const EvalResults& results, const std::filesystem::path& path) {
    engine::write_png(
        path, compose(results.options, results.tiles, contact_sheet_rows(results.options), results.options.scales, 0));
}

void write_level_picture(const EvalResults& results, const std::filesystem::path& path) {
    std::vector<int> scales;
    for (const auto& tile : results.level_tiles)
        if (std::find(scales.begin(), scales.end(), tile.factor) == scales.end()) scales.push_back(tile.factor);
    engine::Image picture = compose(results.options, results.level_tiles, {"full"}, scales, kLabelHeight + 4);
    // The tints of the splat pass's level view (runtime/shaders/splat_lod/common_splat_lod.glsl, level_colour()).
    const std::array<std::array<std::uint8_t, 3>, 4> tints{
        {{204, 204, 204}, {51, 230, 51}, {64, 115, 255}, {255, 64, 51}}};
    const int y0 = picture.height - kLabelHeight;
    for (int level = 0; level < 4; ++level) {
        const int x0 = 4 + level * 40;
        fill_rect(picture, x0, y0 + 2, 10, 10, tints[static_cast<std::size_t>(level)]);
        std::string label = "L";  // (built by appending: GCC 12 warns falsely on "L" + std::string)
        label += std::to_string(level + 1);
        draw_text(picture, x0 + 14, y0 + 3, label);
    }
    engine::write_png(path, picture);
}

}  // namespace splat_lod::eval
