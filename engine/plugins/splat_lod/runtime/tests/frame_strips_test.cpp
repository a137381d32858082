// Strips of tile rows planned from the last frame's (passes/frame_strips.h): the room split between the
// two buffers, neighbours merged while they fit, strips that needed more cut, no strips without a limit.
#include <gtest/gtest.h>

#include "gpu/gpu_layout.h"
#include "passes/frame_strips.h"

using splat_lod::DrawnStrip;
using splat_lod::StripRoom;

TEST(FrameStrips, TheRoomSplitsTheLimitByWhatTheLastFrameNeeded) {
    EXPECT_FALSE(splat_lod::strip_room(0, 1000, 1000, 1).limited()) << "0: no limit";
    // 1000 splats of 48 bytes against 1000 pairs of 17 (one-word keys): 48/65 of the limit for splats.
    const StripRoom room = splat_lod::strip_room(65'000, 1000, 1000, 1);
    ASSERT_EQ(sizeof(splat_lod::gpu::ProjectedSplat), 48u);
    EXPECT_NEAR(room.splats, 1000, 1);  // rounded down
    EXPECT_NEAR(room.pairs, 1000, 1);
    // Each buffer gets at least a quarter of the limit, and half of it with nothing to go by.
    EXPECT_NEAR(splat_lod::strip_room(48'000, 1000, 0, 1).pairs, 12'000 / 17, 1);
    EXPECT_NEAR(splat_lod::strip_room(48'000, 0, 0, 2).splats, 24'000 / 48, 1);
    EXPECT_NEAR(splat_lod::strip_room(48'000, 0, 0, 2).pairs, 24'000 / 25, 1);
}

TEST(FrameStrips, NeighboursMergeWhileTheyFitAndLargerOnesAreCut) {
    const StripRoom room{1000, 2000};  // kStripFill of it: 800 splats, 1600 pairs
    // No limit, no last frame, or a last frame of another size: one strip.
    EXPECT_EQ(splat_lod::plan_strips({}, {{0, 10, 5000, 9000}}, 10).size(), 1u);
    EXPECT_EQ(splat_lod::plan_strips(room, {}, 10).size(), 1u);
    EXPECT_EQ(splat_lod::plan_strips(room, {{0, 12, 100, 100}}, 10).size(), 1u);

    const std::vector<DrawnStrip> last{{0, 3, 300, 500}, {3, 5, 400, 600}, {5, 6, 900, 1000}, {6, 10, 100, 1500}};
    const std::vector<DrawnStrip> plan = splat_lod::plan_strips(room, last, 10);
    // Rows 0–5 merge (700 splats, 1100 pairs); rows 5–6 needed 900 > 800 splats but is one row; rows 6–10
    // needed 1500 pairs: alone, as merging with rows 5–6 would need more.
    ASSERT_EQ(plan.size(), 3u);
    EXPECT_EQ(plan[0].first_row, 0u);
    EXPECT_EQ(plan[0].end_row, 5u);
    EXPECT_EQ(plan[1].first_row, 5u);
    EXPECT_EQ(plan[1].end_row, 6u);
    EXPECT_EQ(plan[2].first_row, 6u);
    EXPECT_EQ(plan[2].end_row, 10u);

    // A strip that needed 2.5 times what the planned fill holds is cut into 3 of equal rows.
    const std::vector<DrawnStrip> cut = splat_lod::plan_strips(room, {{0, 9, 2000, 100}}, 9);
    ASSERT_EQ(cut.size(), 3u);
    for (std::size_t k = 0; k < cut.size(); ++k) {
        EXPECT_EQ(cut[k].first_row, 3 * k);
        EXPECT_EQ(cut[k].end_row, 3 * k + 3);
    }
}
