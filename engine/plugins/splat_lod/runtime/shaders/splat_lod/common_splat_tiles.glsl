// Which raster tiles a projected splat touches (docs/algorithms.md §1, "Tile footprint"). Step 1b
// counts them, the budget trim recounts them after it scales an opacity, step 3 counts them again and
// writes one key per tile: all three call these functions on the same stored values (mean, conic,
// opacity), so the counts and the keys agree. Needs `frame` (FrameUniforms).
//
// A pixel takes part in the splat's blend when o·exp(−½ dᵀQd) ≥ 1/255 at its centre, i.e. when
// dᵀQd ≤ L = 2 ln(255·o), Q the conic (the inverse of the dilated 2D covariance Σ). With
// frame.exact_tiles == 0 they take every tile of the footprint's bounding box instead. Otherwise
// the footprint is, row of tiles by row of tiles, the tiles between the ellipse's leftmost and
// rightmost points over that row's pixel centres: a tile is left out only when no pixel centre in it
// can pass the test.
// The level set is widened by a relative 1e-3 and the spans by 1e-3 px, so that rounding can only
// add a pair, never drop one the raster would draw.

const float TILE_LEVEL_SET_MARGIN = 1.001;
const float TILE_SPAN_MARGIN_PX = 1e-3;

struct TileFootprint {
    vec2 mean;
    float qx, qy, qz;  // the conic
    float level_set;   // L, widened
    ivec2 lo, hi;      // pixel bounding box, clamped to the raster (lo > hi: empty)
    uvec4 rect;        // tiles [x0, x1) × [y0, y1) of the bounding box
};

// The footprint within the raster's pixel rows [row_lo, row_hi] (all of them, or a strip's).
TileFootprint tile_footprint_in_rows(vec2 mean, vec4 conic, float opacity, float row_lo, float row_hi) {
    TileFootprint f;
    f.mean = mean;
    f.qx = conic.x;
    f.qy = conic.y;
    f.qz = conic.z;
    precise float level_set = 2.0 * log(255.0 * opacity) * TILE_LEVEL_SET_MARGIN;
    f.level_set = level_set;
    precise float det_q = f.qx * f.qz - f.qy * f.qy;
    // Σxx = qz/det(Q), Σyy = qx/det(Q): the half extents are sqrt(L·Σxx), sqrt(L·Σyy).
    precise vec2 radius = sqrt(f.level_set * vec2(f.qz, f.qx) / det_q);
    precise vec2 lo = ceil(mean - radius - 0.5 - TILE_SPAN_MARGIN_PX);
    precise vec2 hi = floor(mean + radius - 0.5 + TILE_SPAN_MARGIN_PX);
    vec2 first = vec2(0.0, row_lo), last = vec2(frame.raster_size.x - 1.0, row_hi);
    bool valid = det_q > 0.0 && f.level_set > 0.0 && !any(isnan(lo)) && !any(isnan(hi));
    f.lo = valid ? ivec2(clamp(lo, first, last + 1.0)) : ivec2(1);
    f.hi = valid ? ivec2(clamp(hi, first - 1.0, last)) : ivec2(0);
    if (any(greaterThan(f.lo, f.hi))) {
        f.rect = uvec4(0u);
        return f;
    }
    f.rect = uvec4(uvec2(f.lo) / frame.tile_size, uvec2(f.hi) / frame.tile_size + 1u);
    return f;
}

// The footprint within the rows this run of the steps draws: the whole raster, or with
// SplatPassSettings::frame_memory_limit one strip of tile rows, [strip_first_row, strip_end_row). A
// strip's edges are tile edges, so every tile of a strip gets the pairs it gets without strips.
TileFootprint tile_footprint(vec2 mean, vec4 conic, float opacity) {
    float row_lo = float(frame.strip_first_row * frame.tile_size);
    float row_hi = min(float(frame.strip_end_row * frame.tile_size), frame.raster_size.y) - 1.0;
    return tile_footprint_in_rows(mean, conic, opacity, row_lo, row_hi);
}

// Tiles [x0, x1) of tile row `ty` (within rect.y ≤ ty < rect.w). For pixel-centre offsets
// dy ∈ [a, b] the ellipse's row through dy spans dx = k·dy ± h(dy), k = −qy/qx,
// h = sqrt((L − dy²·det(Q)/qx)/qx); k·dy + h is concave in dy with its maximum at the rightmost
// point, dy* = −qy·sqrt(L/(det(Q)·qz)), so over [a, b] the right edge is at clamp(dy*, a, b) and
// the left edge, by symmetry, at clamp(−dy*, a, b).
uvec2 tile_row_span(TileFootprint f, uint ty) {
    precise float det_q = f.qx * f.qz - f.qy * f.qy;
    int first = max(int(ty * frame.tile_size), f.lo.y);
    int last = min(int(ty * frame.tile_size + frame.tile_size) - 1, f.hi.y);
    precise float a = float(first) + 0.5 - f.mean.y, b = float(last) + 0.5 - f.mean.y;
    precise float k = -f.qy / f.qx;
    precise float dy_star = -f.qy * sqrt(f.level_set / (det_q * f.qz));
    precise float right_dy = clamp(dy_star, a, b), left_dy = clamp(-dy_star, a, b);
    precise float right = k * right_dy + sqrt(max(f.level_set - right_dy * right_dy * det_q / f.qx, 0.0) / f.qx);
    precise float left = k * left_dy - sqrt(max(f.level_set - left_dy * left_dy * det_q / f.qx, 0.0) / f.qx);
    // Pixel columns whose centres lie in [mean.x + left, mean.x + right], within the bounding box.
    float x0 = max(ceil(f.mean.x + left - 0.5 - TILE_SPAN_MARGIN_PX), float(f.lo.x));
    float x1 = min(floor(f.mean.x + right - 0.5 + TILE_SPAN_MARGIN_PX), float(f.hi.x));
    if (!(x0 <= x1)) return uvec2(0u);
    return uvec2(uint(x0) / frame.tile_size, uint(x1) / frame.tile_size + 1u);
}

uint tile_footprint_count(TileFootprint f) {
    uint count = 0u;
    for (uint ty = f.rect.y; ty < f.rect.w; ++ty) {
        uvec2 span = tile_row_span(f, ty);
        count += span.y - span.x;
    }
    return count;
}

// The footprint over the whole raster, whatever rows this run of the steps draws.
TileFootprint whole_footprint(vec2 mean, vec4 conic, float opacity) {
    return tile_footprint_in_rows(mean, conic, opacity, 0.0, frame.raster_size.y - 1.0);
}

// The first tile row in which footprint `f` (whole_footprint) touches a tile (rect.w when none): in strips,
// the strip that holds it counts the splat in the frame's statistics, so that each is counted once.
uint first_tile_row(TileFootprint f) {
    if (frame.exact_tiles == 0u) return f.rect.y;
    for (uint ty = f.rect.y; ty < f.rect.w; ++ty) {
        uvec2 span = tile_row_span(f, ty);
        if (span.y > span.x) return ty;
    }
    return f.rect.w;
}

// The number of tiles a stored splat touches (its keys): 0 for one at or below α = 1/255.
uint splat_tile_count(vec2 mean, vec4 conic, float opacity) {
    if (!(opacity > 1.0 / 255.0)) return 0u;
    TileFootprint f = tile_footprint(mean, conic, opacity);
    return frame.exact_tiles != 0u ? tile_footprint_count(f) : (f.rect.z - f.rect.x) * (f.rect.w - f.rect.y);
}
