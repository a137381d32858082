#pragma once
// What the splat pass drew in a frame, read back from the GPU a few frames late (never stalling
// the frame): `frame_index` says which frame the counts belong to.
#include <array>
#include <cstdint>
#include <string_view>

#include <nlohmann/json.hpp>

namespace plugin_msgs {

struct SplatStatistics {
    static constexpr std::string_view kind = "splat_statistics";

    std::uint64_t frame_index = 0;
    std::uint64_t considered = 0;                        // Gaussians of every splat component
    std::uint64_t visible = 0;                           // after culling (and LOD selection)
    std::array<std::uint64_t, 4> per_level{0, 0, 0, 0};  // visible per LOD level 1..4
    std::uint64_t skipped = 0;                           // not projected: in clusters too small to select (LOD modes)
    std::uint64_t culled = 0;                            // not projected: in clusters outside the view frustum
    std::uint64_t hidden = 0;  // not projected: of components resident but not drawn (a streamer's cut)
    // The splat budget (LodSettings::splat_budget; 0: none). `unbudgeted` is what the selection would
    // have drawn without it; the frame selected with coverage divided by `budget_scale` (β ≥ 1), i.e.
    // with a size threshold of `budget_threshold_px` = β·S_T and coverage ranges β times larger, and
    // dropped Gaussians of coverage below `budget_coverage_cut_px` (0: none) when even the coarsest
    // cut did not fit.
    std::uint64_t splat_budget = 0;
    std::uint64_t unbudgeted = 0;
    double budget_scale = 1.0;
    double budget_threshold_px = 0.0;
    double budget_coverage_cut_px = 0.0;
    std::uint64_t tile_splat_pairs = 0;  // keys the frame needed
    std::uint64_t key_capacity = 0;
    bool overflowed = false;           // the frame needed more keys than the capacity (grown after)
    std::uint64_t resident_bytes = 0;  // GPU bytes held for the scene's splats

    friend bool operator==(const SplatStatistics&, const SplatStatistics&) = default;
};

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(SplatStatistics, frame_index, considered, visible, per_level, skipped,
                                                culled, hidden, splat_budget, unbudgeted, budget_scale,
                                                budget_threshold_px, budget_coverage_cut_px, tile_splat_pairs,
                                                key_capacity, overflowed, resident_bytes)

}  // namespace plugin_msgs
