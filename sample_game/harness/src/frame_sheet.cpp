#include "sample_game/harness/frame_sheet.h"

#include <algorithm>

#include "splat_lod/eval/sheet_drawing.h"

namespace sample_game {
namespace {

constexpr int kGap = 2;

// Area average: every source pixel counts once (a thumbnail of a detailed frame stays calm).
engine::Image shrink(const engine::Image& source, int width) {
    width = std::clamp(width, 1, source.width);
    const int height = std::max(1, width * source.height / source.width);
    engine::Image out{
        width, height,
        std::vector<std::uint8_t>(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4)};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const int sx0 = x * source.width / width, sy0 = y * source.height / height;
            const int sx1 = std::max(sx0 + 1, (x + 1) * source.width / width);
            const int sy1 = std::max(sy0 + 1, (y + 1) * source.height / height);
            int sum[3] = {0, 0, 0}, n = 0;
            for (int sy = sy0; sy < sy1; ++sy)
                for (int sx = sx0; sx < sx1; ++sx, ++n)
                    for (int c = 0; c < 3; ++c) sum[c] += source.pixel(sx, sy)[c];
            std::uint8_t* p = out.pixel(x, y);
            for (int c = 0; c < 3; ++c) p[c] = static_cast<std::uint8_t>(sum[c] / n);
            p[3] = 255;
        }
    return out;
}

}  // namespace

FrameSheet::FrameSheet(int thumbnail_width, int columns)
    : thumbnail_width_(thumbnail_width), columns_(std::max(1, columns)) {}

void FrameSheet::add(const engine::Image& frame, const std::string& label) {
    if (frame.width <= 0 || frame.height <= 0) return;
    tiles_.push_back({shrink(frame, thumbnail_width_), label});
}

void FrameSheet::add_blank(const std::string& label) {
    tiles_.push_back({engine::Image{}, label});
}

void FrameSheet::write(const std::filesystem::path& path) const {
    if (tiles_.empty()) return;
    int tile_w = 0, tile_h = 0;
    for (const auto& t : tiles_) {
        tile_w = std::max(tile_w, t.image.width);
        tile_h = std::max(tile_h, t.image.height);
    }
    const int columns = std::min(columns_, static_cast<int>(tiles_.size()));
    const int rows = (static_cast<int>(tiles_.size()) + columns - 1) / columns;
    const int cell_h = tile_h + splat_lod::eval::kLabelHeight;
    engine::Image sheet = splat_lod::eval::black_image(columns * (tile_w + kGap), rows * (cell_h + kGap));
    for (std::size_t i = 0; i < tiles_.size(); ++i) {
        const int x0 = static_cast<int>(i) % columns * (tile_w + kGap);
        const int y0 = static_cast<int>(i) / columns * (cell_h + kGap);
        // Cut to the tile (about 6 px per character), so that a long label does not run into the next.
        splat_lod::eval::draw_text(sheet, x0 + 4, y0 + 4,
                                   tiles_[i].label.substr(0, static_cast<std::size_t>(std::max(0, (tile_w - 4) / 6))));
        const engine::Image& image = tiles_[i].image;
        for (int y = 0; y < image.height; ++y)
            std::copy_n(image.pixel(0, y), static_cast<std::size_t>(image.width) * 4,
                        sheet.pixel(x0, y0 + splat_lod::eval::kLabelHeight + y));
    }
    engine::write_png(path, sheet);
}

}  // namespace sample_game
