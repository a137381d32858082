#pragma once
// Drawing on the evaluation's pictures (contact sheet, level picture, upscale crops, temporal strips):
// opaque black canvases, tiles scaled into them, filled rectangles and white labels drawn with
// stb_easy_font's quads (no font files).
#include <array>
#include <cstdint>
#include <string>

#include "engine/render/image.h"

namespace splat_lod::eval {

// Height of a label line in pixels (stb_easy_font draws about 7 px tall, 6 px per character).
constexpr int kLabelHeight = 16;

engine::Image black_image(int width, int height);
void fill_rect(engine::Image& image, int x0, int y0, int w, int h, const std::array<std::uint8_t, 3>& colour);
// `tile` drawn into the tw × th rectangle at (x0, y0) of `sheet`, which must hold it: area average
// when shrinking (a full-resolution tile looks like its source), nearest neighbour when enlarging (a
// small tile shows its few pixels).
void draw_scaled(engine::Image& sheet, const engine::Image& tile, int x0, int y0, int tw, int th);
// White text with its top left at (x0, y0), clipped to the image.
void draw_text(engine::Image& image, int x0, int y0, const std::string& text);

}  // namespace splat_lod::eval
