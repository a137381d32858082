// The chunk streamer (splat_lod/stream/chunk_streamer.h) with chunk groups: the small synthetic world
// of chunk_streamer_test_helpers.h under a quadtree of groups, drawn as a cut without holes or overlap
// while the camera flies in and out, with a missing group, groups off, the memory budget, and a
// binding splat budget that coarsens the cut; nodes and levels that fade in and out.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "chunk_streamer_test_helpers.h"
#include "engine/core/error.h"
#include "engine/core/message_bus.h"
#include "splat_lod/core/chunk_quadtree.h"
#include "splat_lod/core/world_manifest.h"
#include "splat_lod/msgs/splat_statistics.h"
#include "splat_lod/msgs/stream_events.h"
#include "splat_lod/stream/chunk_streamer.h"
#include "splat_lod/stream/splat_budget.h"

namespace sw = splat_lod::world;
using namespace chunk_streamer_test;
using plugin_msgs::StreamEventType;

namespace {

// A world of side × side chunks (side a power of 2, the chunks of make_world() when side is kGrid, with
// cells from −side/2 as generated) under a full quadtree of groups: depth d pools cells of
// 0.5 · 2^(d − 1) m (depth 1 drawn from 50 m at f = 100 px and 1 px, depth 2 from 100 m), 30 Gaussians
// a group, all of stream level 4. Groups are listed by depth, each in the order of its first chunk.
sw::WorldManifest make_deep_world(int side) {
    sw::WorldManifest world;
    world.size_m = static_cast<float>(side) * kChunkSize;
    world.chunk_size_m = kChunkSize;
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) world.chunks.push_back(make_chunk(i, j));
    for (sw::ChunkEntry& c : world.chunks) c.cell -= glm::ivec2(side / 2);
    for (int depth = 1; (1 << depth) <= side; ++depth) {
        std::map<std::pair<int, int>, std::size_t> made;  // cell → index in world.groups
        for (const sw::ChunkEntry& c : world.chunks) {
            const glm::ivec2 g = sw::group_of_chunk(c.cell, side, depth);
            const auto [it, fresh] = made.try_emplace({g.x, g.y}, world.groups.size());
            if (fresh) {
                sw::ChunkEntry e = c;
                e.id = sw::group_id(depth, g);
                e.file = e.id + ".ply";
                e.cell = g;
                e.depth = depth;
                e.cell_m = 0.5f * static_cast<float>(1 << (depth - 1));
                e.prefix_count = {30, 30, 30, 30};
                e.levels = {};
                e.file_bytes = e.prefix_bytes(1);
                world.groups.push_back(e);
            }
            sw::ChunkEntry& e = world.groups[it->second];
            e.bounds_min = glm::min(e.bounds_min, c.bounds_min);
            e.bounds_max = glm::max(e.bounds_max, c.bounds_max);
        }
    }
    return world;
}

// The 4 × 4 chunks of make_world() under 2 × 2 groups of depth 1 and a root of depth 2.
sw::WorldManifest make_grouped_world() {
    return make_deep_world(kGrid);
}

// Over every chunk, the opacities of the nodes on its path to the root (chunk_streamer.h, "fades"):
// never above 1 (nothing drawn twice over the same ground), above 0 (no hole), and exactly 1 when at
// most two of them are on screen (a cross-fade, or one node alone). With `settled`, exactly one node is
// drawn, at opacity 1.
std::vector<std::string> coverage_problems(const Harness& h, const sw::WorldManifest& world, bool settled = false) {
    std::vector<std::string> problems;
    const int count = sw::chunks_per_side(world);
    for (const sw::ChunkEntry& c : world.chunks) {
        std::vector<std::string> path{c.id};
        for (int depth = 1; depth <= 2; ++depth)
            path.push_back(sw::group_id(depth, sw::group_of_chunk(c.cell, count, depth)));
        float sum = 0.0f;
        int on_screen = 0;
        for (const std::string& id : path) {
            const float o = h.sink.drawn_opacity(id);
            sum += o;
            on_screen += o > 0.0f ? 1 : 0;
        }
        const std::string what =
            c.id + ": opacities sum to " + std::to_string(sum) + " over " + std::to_string(on_screen) + " nodes";
        if (sum > 1.0f + 1e-5f || !(sum > 0.0f))
            problems.push_back(what);
        else if (on_screen <= 2 && std::abs(sum - 1.0f) > 1e-5f)
            problems.push_back(what);
        else if (settled && (on_screen != 1 || sum != 1.0f))
            problems.push_back(what + " (settled)");
    }
    return problems;
}

}  // namespace

TEST(ChunkStreamerGroups, FarViewLoadsTheRootOnly) {
    Harness h(sync_settings(), nullptr, make_grouped_world());
    h.steps({20.0f, 400.0f, 20.0f}, 12);  // loaded, then faded in over fade_frames (4) updates
    EXPECT_TRUE(h.sink.drawn("group_2_+000_+000"));
    EXPECT_EQ(h.sink.total, 30u * kPerGaussian) << "only the root is resident";
    EXPECT_EQ(h.streamer.residency().drawn_groups, 1u);
    EXPECT_EQ(h.streamer.residency().drawn_chunks, 0u);
    EXPECT_TRUE(h.status("group_2_+000_+000").in_cut);
    EXPECT_FALSE(h.status("chunk_0_0").in_cut);
    EXPECT_TRUE(h.sink.violations.empty());
    EXPECT_TRUE(coverage_problems(h, make_grouped_world(), true).empty());
}

TEST(ChunkStreamerGroups, FlyingInAndOutNeverLeavesAHoleOrDrawsTwice) {
    sw::StreamerSettings settings = sync_settings();
    settings.upload_budget_bytes_per_frame = 200 * kPerGaussian;  // levels arrive over several frames
    settings.unload_delay_frames = 3;
    const sw::WorldManifest world = make_grouped_world();
    Harness h(settings, nullptr, world);
    glm::vec3 eye{20.0f, 400.0f, 20.0f};
    h.steps(eye, 12);  // the root loaded and faded in
    std::set<std::string> seen_drawn;
    for (int k = 0; k < 160; ++k) {  // down to the ground in the corner chunk and back up
        const float t = k < 80 ? static_cast<float>(k) / 79.0f : static_cast<float>(159 - k) / 79.0f;
        eye = glm::mix(glm::vec3(20.0f, 400.0f, 20.0f), glm::vec3(2.0f, 1.5f, 2.0f), std::pow(t, 0.4f));
        h.step(eye);
        for (const std::string& problem : coverage_problems(h, world)) ADD_FAILURE() << "step " << k << ": " << problem;
        for (const auto& [id, visible] : h.sink.shown)
            if (h.sink.drawn(id)) seen_drawn.insert(id);
    }
    EXPECT_TRUE(seen_drawn.count("chunk_0_0"));
    EXPECT_TRUE(seen_drawn.count("group_1_+001_+001"));
    EXPECT_TRUE(seen_drawn.count("group_1_+000_+000"));
    EXPECT_TRUE(seen_drawn.count("group_2_+000_+000"));
    EXPECT_TRUE(h.sink.violations.empty()) << h.sink.violations.front();
}

// Descending fast, the cut moves from the root to the depth-1 groups and on to the chunks before the
// root has faded out. While the chunks load, the complete depth-1 groups stand in for them: the root,
// still resident, must not be drawn again in their place (it was, and the walkthrough's descent drew
// coarse groups for three frames longer, 3 dB below the reference). The depth-1 groups, replaced
// half faded in, hand over to the chunks with the root's fade-out: every chunk's ground sums to 1.
TEST(ChunkStreamerGroups, ACoarserNodeDoesNotComeBackOnceFinerOnesAreIn) {
    sw::StreamerSettings settings = sync_settings();
    settings.upload_budget_bytes_per_frame = 200 * kPerGaussian;  // levels arrive over several frames
    const sw::WorldManifest world = make_grouped_world();
    Harness h(settings, nullptr, world);
    h.steps({20.0f, 400.0f, 20.0f}, 12);  // the root loaded and faded in
    const std::vector<std::string> depth1 = {"group_1_+000_+000", "group_1_+001_+000", "group_1_+000_+001",
                                             "group_1_+001_+001"};
    bool depth1_drawn = false, root_left_while_shown = false, root_back = false;
    // Two updates where the depth-1 groups are the cut (they load and are drawn), then where the chunks are.
    for (int k = 0; k < 16; ++k) {
        h.step(k < 2 ? glm::vec3(20.0f, 90.0f, 20.0f) : glm::vec3(20.0f, 30.0f, 20.0f));
        bool all_depth1_complete = true;
        for (const std::string& id : depth1) {
            depth1_drawn = depth1_drawn || h.status(id).drawn;
            all_depth1_complete = all_depth1_complete && h.status(id).finest_resident_level != 0;
        }
        const sw::ChunkStatus root = h.status("group_2_+000_+000");
        if (depth1_drawn && !root.drawn && h.sink.drawn_opacity("group_2_+000_+000") > 0.0f)
            root_left_while_shown = true;
        if (depth1_drawn && root.drawn && all_depth1_complete) {
            root_back = true;
            ADD_FAILURE() << "step " << k << ": the root is drawn again while every depth-1 group is complete";
        }
        for (const std::string& problem : coverage_problems(h, world)) ADD_FAILURE() << "step " << k << ": " << problem;
    }
    EXPECT_TRUE(depth1_drawn);
    EXPECT_TRUE(root_left_while_shown) << "the case: the root still fading out when the depth-1 groups are drawn";
    EXPECT_FALSE(root_back);
    EXPECT_TRUE(h.sink.violations.empty()) << h.sink.violations.front();
}

TEST(ChunkStreamerGroups, NearViewDrawsChunksAndReleasesGroups) {
    sw::StreamerSettings settings = sync_settings();
    settings.group_grazing_deg = 0.0f;  // by the cell's edge: every group is too near
    Harness h(settings, nullptr, make_grouped_world());
    h.steps({20.0f, 400.0f, 20.0f}, 3);
    h.steps({5.0f, 1.0f, 5.0f}, 6);  // inside chunk_0_0: its group 1 is 0 m away
    EXPECT_TRUE(h.sink.drawn("chunk_0_0"));
    EXPECT_FALSE(h.sink.drawn("group_2_+000_+000"));
    EXPECT_EQ(h.sink.level_bytes.count({"group_2_+000_+000", 4}), 0u) << "released once replaced";
    // Chunks more than 50 m away are drawn from their depth-1 group... none here (the world is 40 m):
    EXPECT_EQ(h.streamer.residency().drawn_groups, 0u);
    EXPECT_EQ(h.streamer.residency().drawn_chunks, 16u);
}

TEST(ChunkStreamerGroups, AtAGrazingAngleAFarGroupStandsInForItsChunks) {
    const sw::WorldManifest world = make_grouped_world();
    sw::StreamerSettings settings = sync_settings();
    settings.group_grazing_deg = 90.0f;  // the box's area at every elevation (a / sin 90°)
    Harness h(settings, nullptr, world);
    h.steps({20.0f, 400.0f, 20.0f}, 3);
    // 1 m above the corner of chunk_0_0: the far depth-1 group is 21.2 m away, its 0.5 m cell
    // 2.36 px by its edge, but its box (20.5 × 2.5 × 20.5 m, widened by the cell) shows 0.17 of its
    // ground area from here (a = 2.5 · (0.707 + 0.707) / 20.5): 0.98 px ≤ 1. The depth-1 group at
    // x = 0…20, z = 20…40 is 15 m away: 3.33 px by its edge, 1.26 px foreshortened, so not.
    h.steps({5.0f, 1.0f, 5.0f}, 8);
    EXPECT_TRUE(h.sink.drawn("group_1_+001_+001"));
    EXPECT_TRUE(h.sink.drawn("chunk_0_0"));
    EXPECT_EQ(h.streamer.residency().drawn_groups, 1u);
    EXPECT_EQ(h.streamer.residency().drawn_chunks, 12u);
    for (const std::string& problem : coverage_problems(h, world, true)) ADD_FAILURE() << problem;
    // From straight above at about the same distance (20.2 m over the box's top) it is 2.47 px: its
    // chunks are drawn.
    h.steps({30.0f, 22.2f, 30.0f}, 8);
    EXPECT_FALSE(h.sink.drawn("group_1_+001_+001"));
    EXPECT_EQ(h.streamer.residency().drawn_groups, 0u);
    EXPECT_EQ(h.streamer.residency().drawn_chunks, 16u);
    for (const std::string& problem : coverage_problems(h, world, true)) ADD_FAILURE() << problem;
}

// The update looks at the cut and what is live, not at the whole world: a world 64 times larger
// (4,096 chunks under 1,365 groups against 64 under 21) costs it a few more nodes, those of the
// deeper quadtree above the cut and the cut's coarser groups farther away (89 against 57 when written).
TEST(ChunkStreamerGroups, AnUpdateLooksAtTheViewNotTheWholeWorld) {
    std::uint64_t looked_at[2] = {0, 0};
    std::size_t drawn_chunks[2] = {0, 0};
    for (const int k : {0, 1}) {
        const sw::WorldManifest world = make_deep_world(k == 0 ? 8 : 64);
        Harness h(sync_settings(), nullptr, world);
        h.steps({15.0f, 3.0f, 15.0f}, 20);  // 3 m above chunk (1, 1), near the world's corner
        looked_at[k] = h.streamer.stats().nodes_last_update;
        drawn_chunks[k] = h.streamer.residency().drawn_chunks;
        EXPECT_TRUE(h.sink.drawn("chunk_1_1"));
        EXPECT_TRUE(h.sink.violations.empty());
    }
    EXPECT_EQ(drawn_chunks[0], drawn_chunks[1]) << "the same chunks near the camera";
    EXPECT_GT(looked_at[0], 0u);
    EXPECT_LE(looked_at[1], 2 * looked_at[0]) << looked_at[0] << " nodes for 85, " << looked_at[1] << " for 5,461";
}

TEST(ChunkStreamerGroups, AMissingGroupIsReportedAndItsChunksDrawn) {
    Harness h(sync_settings(), nullptr, make_grouped_world());
    h.source.missing.insert("group_2_+000_+000.ply");
    h.steps({20.0f, 400.0f, 20.0f}, 14);  // loaded, then faded in
    const auto failed = h.of(StreamEventType::failed, "group_2_+000_+000");
    ASSERT_EQ(failed.size(), 1u);
    EXPECT_NE(failed[0].second.message.find("group_2_+000_+000.ply"), std::string::npos);
    EXPECT_FALSE(h.sink.drawn("group_2_+000_+000"));
    EXPECT_EQ(h.streamer.residency().drawn_groups, 4u) << "the depth-1 groups stand in for the root";
    for (const std::string& problem : coverage_problems(h, make_grouped_world(), true)) ADD_FAILURE() << problem;
}

TEST(ChunkStreamerGroups, GroupsOffStreamsChunksOnly) {
    sw::StreamerSettings settings = sync_settings();
    settings.group_cell_px = 0.0f;
    Harness h(settings, nullptr, make_grouped_world());
    h.steps({20.0f, 400.0f, 20.0f}, 4);
    EXPECT_EQ(h.streamer.residency().drawn_chunks, 16u);
    EXPECT_EQ(h.streamer.residency().groups.resident, 0u);
    for (const auto& [key, bytes] : h.sink.level_bytes) EXPECT_EQ(key.first.rfind("chunk_", 0), 0u) << key.first;
}

TEST(ChunkStreamerGroups, MemoryBudgetHoldsWhileTheCutMoves) {
    sw::StreamerSettings settings = sync_settings();
    settings.memory_budget_bytes = 4 * (10 + 40) * kPerGaussian + 60 * kPerGaussian;
    settings.upload_budget_bytes_per_frame = 100 * kPerGaussian;
    Harness h(settings, nullptr, make_grouped_world());
    for (int k = 0; k < 60; ++k)
        h.step(glm::mix(glm::vec3(20.0f, 400.0f, 20.0f), glm::vec3(5.0f, 2.0f, 5.0f), static_cast<float>(k) / 59.0f));
    EXPECT_TRUE(h.sink.violations.empty());
    EXPECT_GT(h.streamer.residency().drawn_chunks, 0u);
}

TEST(ChunkStreamerGroups, ABindingSplatBudgetMakesTheCutCoarser) {
    EXPECT_EQ(sw::next_group_cell_scale(1.0f, 500, 0), 1.0f) << "no budget";
    EXPECT_EQ(sw::next_group_cell_scale(1.0f, 150, 200), 1.0f) << "within the budget, at 1";
    EXPECT_NEAR(sw::next_group_cell_scale(1.0f, 210, 200), std::sqrt(210.0f / 200.0f), 1e-6f);
    EXPECT_NEAR(sw::next_group_cell_scale(1.0f, 2000, 200), std::exp2(0.25f), 1e-6f) << "at most 2^(1/4) a step";
    EXPECT_EQ(sw::next_group_cell_scale(3.0f, 180, 200), 3.0f) << "between 70 % and 100 %: held";
    EXPECT_NEAR(sw::next_group_cell_scale(3.0f, 100, 200), 3.0f / std::exp2(0.125f), 1e-6f);
    EXPECT_EQ(sw::next_group_cell_scale(1.01f, 0, 200), 1.0f);

    // 60 m above the middle of the world (the boxes 60 m away): the depth-1 groups (0.5 m cells,
    // 0.83 px) are the cut at 1 px, the root (1 m cells, 1.67 px) once the switch is scaled by 2. The
    // renderer's statistics reach the budget's controller on the bus, and its scale the cut: a budget
    // drawn 4× over scales it by √4 = 2 in steps of at most 2^(1/4).
    engine::MessageBus bus;
    Harness h(sync_settings(), &bus, make_grouped_world());
    sw::SplatBudgetController budget(bus);
    h.steps({20.0f, 62.0f, 20.0f}, 4);
    EXPECT_EQ(h.streamer.residency().drawn_groups, 4u);
    EXPECT_EQ(h.streamer.group_cell_scale(), 1.0f);
    EXPECT_EQ(budget.update(), 1.0f) << "no statistics yet";
    plugin_msgs::SplatStatistics over;
    over.splat_budget = 100;
    over.unbudgeted = 400;
    for (int k = 0; k < 4; ++k) {
        bus.publish(over);
        h.step({20.0f, 62.0f, 20.0f}, {}, budget.update());
    }
    EXPECT_NEAR(budget.cut_scale(), 2.0f, 1e-5f);
    EXPECT_NEAR(h.streamer.group_cell_scale(), 2.0f, 1e-5f);
    for (int k = 0; k < 3; ++k) h.step({20.0f, 62.0f, 20.0f}, {}, budget.update());  // no new statistics: held
    EXPECT_NEAR(h.streamer.group_cell_scale(), 2.0f, 1e-5f);
    EXPECT_TRUE(h.status("group_2_+000_+000").in_cut);
    EXPECT_TRUE(h.sink.drawn("group_2_+000_+000"));
    EXPECT_EQ(h.streamer.residency().drawn_groups, 1u);
}

// An import's quadtree (ChunkEntry::span): the four chunks of the corner group_1_+000_+000 as one chunk
// of span 1, which hangs from the root directly (no depth-1 group over it). Flying in and out, it
// cross-fades with the root like any node: never drawn with the root, no hole, drawn up close.
TEST(ChunkStreamerGroups, AChunkOfSeveralCellsHangsFromTheGroupAboveItsSpan) {
    sw::WorldManifest world = make_grouped_world();
    const int count = sw::chunks_per_side(world);
    sw::ChunkEntry merged = world.chunks.front();
    merged.id = "chunk_merged";
    merged.file = "chunk_merged.ply";
    merged.span = 1;
    std::vector<sw::ChunkEntry> chunks;
    for (const sw::ChunkEntry& c : world.chunks) {
        if (sw::group_of_chunk(c.cell, count, 1) != glm::ivec2(0, 0)) {
            chunks.push_back(c);
            continue;
        }
        merged.cell = glm::min(merged.cell, c.cell);
        merged.bounds_min = glm::min(merged.bounds_min, c.bounds_min);
        merged.bounds_max = glm::max(merged.bounds_max, c.bounds_max);
    }
    chunks.insert(chunks.begin(), merged);
    world.chunks = chunks;
    std::erase_if(world.groups, [](const sw::ChunkEntry& g) { return g.id == "group_1_+000_+000"; });

    Harness h(sync_settings(), nullptr, world);
    h.steps({20.0f, 400.0f, 20.0f}, 12);
    EXPECT_TRUE(h.sink.drawn("group_2_+000_+000"));
    EXPECT_FALSE(h.sink.drawn("chunk_merged")) << "the root covers it";
    for (int k = 0; k < 80; ++k) {
        const float t = static_cast<float>(k) / 79.0f;
        h.step(glm::mix(glm::vec3(20.0f, 400.0f, 20.0f), glm::vec3(5.0f, 1.5f, 5.0f), std::pow(t, 0.4f)));
        for (const std::string& problem : coverage_problems(h, world)) ADD_FAILURE() << "step " << k << ": " << problem;
    }
    h.steps({5.0f, 1.5f, 5.0f}, 8);
    EXPECT_TRUE(h.sink.drawn("chunk_merged"));
    EXPECT_FALSE(h.sink.drawn("group_2_+000_+000"));
    EXPECT_TRUE(coverage_problems(h, world, true).empty());
    EXPECT_TRUE(h.sink.violations.empty()) << h.sink.violations.front();
}

// Anticipation (chunk_streamer.h): climbing 5 m per update straight above the world, the root (drawn
// from 100 m) enters the cut anticipation_updates (4 by default, 2, 0) updates earlier with the camera's
// velocity than without, so its cross-fade ends about when the switch is due; descending, the finer
// groups enter the cut at the same update with or without it (refinement is never delayed). No hole or
// overlap meanwhile.
TEST(ChunkStreamerGroups, TheCutCoarsensAheadOfAClimbingCameraOnly) {
    const sw::WorldManifest world = make_grouped_world();
    // The first update at which `id` is in the cut, moving from y0 by dy per update, the velocity given to
    // a cut anticipating `ahead` updates (0: the velocity is not given).
    const auto first_in_cut = [&](float y0, float dy, int ahead, const std::string& id) {
        sw::StreamerSettings settings = sync_settings();
        settings.anticipation_updates = ahead;
        Harness h(settings, nullptr, world);
        h.steps({20.0f, y0, 20.0f}, 12);
        for (int k = 0; k < 40; ++k) {
            h.step({20.0f, y0 + dy * static_cast<float>(k + 1), 20.0f}, {0.0f, dy, 0.0f});
            for (const std::string& problem : coverage_problems(h, world))
                ADD_FAILURE() << "update " << k << ": " << problem;
            if (h.status(id).in_cut) return k;
        }
        return -1;
    };
    const int climb = first_in_cut(62.0f, 5.0f, 0, "group_2_+000_+000");
    ASSERT_GT(climb, 4) << "the climb starts well below the root's switch";
    EXPECT_EQ(first_in_cut(62.0f, 5.0f, sw::StreamerSettings{}.anticipation_updates, "group_2_+000_+000"), climb - 4);
    EXPECT_EQ(first_in_cut(62.0f, 5.0f, 2, "group_2_+000_+000"), climb - 2);
    const int descent = first_in_cut(200.0f, -5.0f, 0, "group_1_+000_+000");
    ASSERT_GT(descent, 4);
    EXPECT_EQ(first_in_cut(200.0f, -5.0f, 4, "group_1_+000_+000"), descent);

    Harness h(sync_settings(), nullptr, world);
    EXPECT_THROW(h.streamer.update({{20.0f, 62.0f, 20.0f}, kFocal, 0, {0.0f, NAN, 0.0f}}), engine::Error);
}

// Fades (chunk_streamer.h): when the depth-1 groups replace the root, the root fades out while they
// fade in, one step of 1/8 per update, the opacities summing to 1; the root stays resident and shown
// until its opacity reaches 0. With fade_frames = 0 the swap happens in one update.
TEST(ChunkStreamerFades, ANodeThatReplacesAnotherCrossFadesAndStaysUntilGone) {
    for (const int fade_frames : {8, 0}) {
        SCOPED_TRACE("fade_frames " + std::to_string(fade_frames));
        sw::StreamerSettings settings = sync_settings();
        settings.fade_frames = fade_frames;
        Harness h(settings, nullptr, make_grouped_world());
        h.steps({20.0f, 400.0f, 20.0f}, 12);
        ASSERT_EQ(h.sink.drawn_opacity("group_2_+000_+000"), 1.0f);
        std::vector<float> root, group;
        for (int k = 0; k < 14; ++k) {
            h.step({20.0f, 62.0f, 20.0f});
            root.push_back(h.sink.drawn_opacity("group_2_+000_+000"));
            group.push_back(h.sink.drawn_opacity("group_1_+000_+000"));
            EXPECT_NEAR(root.back() + group.back(), 1.0f, 1e-6f) << "update " << k;
            if (root.back() > 0.0f) {
                EXPECT_GT(h.sink.level_bytes.count({"group_2_+000_+000", 4}), 0u) << "kept while on screen";
            }
        }
        // The swap starts once the groups are complete; from then on one step per update.
        const auto start = std::find_if(group.begin(), group.end(), [](float o) { return o > 0.0f; });
        ASSERT_NE(start, group.end());
        const int steps = std::max(fade_frames, 1);
        for (int i = 0; i < steps && start + i != group.end(); ++i)
            EXPECT_NEAR(*(start + i), static_cast<float>(i + 1) / static_cast<float>(steps), 1e-6f);
        EXPECT_EQ(group.back(), 1.0f);
        EXPECT_EQ(root.back(), 0.0f);
        EXPECT_FALSE(h.sink.shown["group_2_+000_+000"]) << "hidden once faded out";
        EXPECT_TRUE(h.sink.violations.empty()) << h.sink.violations.front();
    }
}

// A finer stream level that arrives while its chunk is on screen fades in by itself: its opacity
// climbs 1/8, 2/8, … 1 over the updates after its upload (fade_frames 8), while the chunk's level 4
// stays at 1.
TEST(ChunkStreamerFades, ALevelThatArrivesOnScreenFadesIn) {
    sw::StreamerSettings settings = sync_settings();
    settings.fade_frames = 8;
    Harness h(settings);
    h.steps(before_chunk_0_0(100.0f), 12);  // level 4 only, faded in
    ASSERT_EQ(h.sink.drawn_opacity("chunk_0_0"), 1.0f);
    ASSERT_EQ(h.sink.level_bytes.count({"chunk_0_0", 3}), 0u);
    std::vector<float> level3;
    for (int k = 0; k < 12; ++k) {
        h.step(before_chunk_0_0(50.0f));  // within level 3's 60 m
        const auto it = h.sink.opacity.find({"chunk_0_0", 3});
        if (it != h.sink.opacity.end()) level3.push_back(it->second);
        EXPECT_EQ(h.sink.drawn_opacity("chunk_0_0"), 1.0f);
    }
    ASSERT_GE(level3.size(), 8u);  // from the update of its upload on
    for (std::size_t i = 0; i < 8; ++i) EXPECT_NEAR(level3[i], static_cast<float>(i + 1) / 8.0f, 1e-6f) << i;
    EXPECT_EQ(level3.back(), 1.0f);
    EXPECT_TRUE(h.sink.violations.empty()) << h.sink.violations.front();
}
