#include "splat_lod/eval/sheet_drawing.h"

#include <algorithm>
#include <vector>

#include <stb/stb_easy_font.h>

namespace splat_lod::eval {

void draw_text(engine::Image& image, int x0, int y0, const std::string& text) {
    std::vector<char> buffer(text.begin(), text.end());
    buffer.push_back('\0');
    struct Vertex {
        float x, y, z;
        unsigned char colour[4];
    };
    std::vector<Vertex> vertices(4 * 400);
    unsigned char white[4] = {255, 255, 255, 255};
    const int quads = stb_easy_font_print(0.0f, 0.0f, buffer.data(), white, vertices.data(),
                                          static_cast<int>(vertices.size() * sizeof(Vertex)));
    for (int q = 0; q < quads; ++q) {
        const Vertex& a = vertices[static_cast<std::size_t>(q) * 4];
        const Vertex& b = vertices[static_cast<std::size_t>(q) * 4 + 2];
        for (int y = static_cast<int>(a.y); y < static_cast<int>(b.y); ++y)
            for (int x = static_cast<int>(a.x); x < static_cast<int>(b.x); ++x)
                if (x0 + x >= 0 && x0 + x < image.width && y0 + y >= 0 && y0 + y < image.height)
                    std::fill_n(image.pixel(x0 + x, y0 + y), 3, std::uint8_t{255});
    }
}

engine::Image black_image(int width, int height) {
    engine::Image image{width, height, {}};
    image.rgba.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4, 0);
    for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
    return image;
}

void fill_rect(engine::Image& image, int x0, int y0, int w, int h, const std::array<std::uint8_t, 3>& colour) {
    for (int y = std::max(0, y0); y < std::min(image.height, y0 + h); ++y)
        for (int x = std::max(0, x0); x < std::min(image.width, x0 + w); ++x)
            std::copy_n(colour.begin(), 3, image.pixel(x, y));
}

void draw_scaled(engine::Image& sheet, const engine::Image& tile, int x0, int y0, int tw, int th) {
    for (int y = 0; y < th; ++y)
        for (int x = 0; x < tw; ++x) {
            const int sx0 = x * tile.width / tw, sy0 = y * tile.height / th;
            const int sx1 = std::max(sx0 + 1, (x + 1) * tile.width / tw),
                      sy1 = std::max(sy0 + 1, (y + 1) * tile.height / th);
            int sum[3] = {0, 0, 0}, n = 0;
            for (int sy = sy0; sy < sy1; ++sy)
                for (int sx = sx0; sx < sx1; ++sx, ++n)
                    for (int c = 0; c < 3; ++c) sum[c] += tile.pixel(sx, sy)[c];
            for (int c = 0; c < 3; ++c) sheet.pixel(x0 + x, y0 + y)[c] = static_cast<std::uint8_t>(sum[c] / n);
        }
}

}  // namespace splat_lod::eval
