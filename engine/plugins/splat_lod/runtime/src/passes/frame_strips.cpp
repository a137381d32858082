// Strips of tile rows (frame_strips.h).
#include "passes/frame_strips.h"

#include <algorithm>
#include <cmath>

#include "gpu/gpu_layout.h"

namespace splat_lod {
namespace {

// How many times kStripFill of the room `s` needs (0 for an empty strip).
double parts_needed(const StripRoom& room, const DrawnStrip& s) {
    return std::max(double(s.splats) / (kStripFill * room.splats), double(s.pairs) / (kStripFill * room.pairs));
}

// `s` cut into as many equal runs of rows as its need asks (its counts shared out evenly).
void cut(const StripRoom& room, const DrawnStrip& s, std::vector<DrawnStrip>& out) {
    const std::uint32_t rows = s.end_row - s.first_row;
    const auto parts = static_cast<std::uint32_t>(std::clamp(std::ceil(parts_needed(room, s)), 1.0, double(rows)));
    for (std::uint32_t k = 0; k < parts; ++k)
        out.push_back(
            {s.first_row + rows * k / parts, s.first_row + rows * (k + 1) / parts, s.splats / parts, s.pairs / parts});
}

}  // namespace

StripRoom strip_room(std::uint64_t limit, std::uint64_t splats, std::uint64_t pairs, std::uint32_t key_words) {
    if (limit == 0) return {};
    // A pair is its key and value, the sort's copy of both and half a byte of the sort's histograms
    // (RadixSort::bytes); a byte covers that and the scan's.
    const double splat_bytes = sizeof(gpu::ProjectedSplat), pair_bytes = 2.0 * 4.0 * (key_words + 1) + 1.0;
    const double s = double(splats) * splat_bytes, p = double(pairs) * pair_bytes;
    const double share = s + p > 0 ? std::clamp(s / (s + p), 0.25, 0.75) : 0.5;
    const auto most = [](double bytes, double each) {
        return static_cast<std::uint32_t>(std::clamp(std::floor(bytes / each), 1.0, 4294967294.0));
    };
    return {most(double(limit) * share, splat_bytes), most(double(limit) * (1.0 - share), pair_bytes)};
}

std::vector<DrawnStrip> plan_strips(const StripRoom& room, const std::vector<DrawnStrip>& last, std::uint32_t rows) {
    if (!room.limited() || last.empty() || last.back().end_row != rows) return {{0, rows, 0, 0}};
    std::vector<DrawnStrip> merged;
    for (const DrawnStrip& s : last) {
        if (!merged.empty()) {
            DrawnStrip both = merged.back();
            both.end_row = s.end_row;
            both.splats += s.splats;
            both.pairs += s.pairs;
            if (parts_needed(room, both) <= 1.0) {
                merged.back() = both;
                continue;
            }
        }
        merged.push_back(s);
    }
    std::vector<DrawnStrip> plan;
    for (const DrawnStrip& s : merged) cut(room, s, plan);
    return plan;
}

}  // namespace splat_lod
