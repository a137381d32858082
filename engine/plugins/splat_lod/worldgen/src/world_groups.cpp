// Chunk groups (world/world_groups.h): the quadtree over the chunk grid and the build of every group of
// a world from its chunk files (the pooling itself: group_pooling.h).
#include "splat_lod/worldgen/world_groups.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <sstream>

#include "engine/core/error.h"
#include "group_pooling.h"
#include "splat_lod/core/chunk_reader.h"
#include "splat_lod/core/chunk_writer.h"
#include "splat_lod/core/parallel_for.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/core/stream_levels.h"

namespace splat_lod::world {

namespace fs = std::filesystem;

std::string check_group_options(const GroupOptions& o, float chunk_size_m) {
    if (!o.enabled) return {};
    if (!(o.base_cell_m > 0.0f) || !std::isfinite(o.base_cell_m)) return "the group cell must be positive";
    if (!(o.fill >= 1.0f && o.fill <= 4.0f)) return "the group fill must be 1 to 4";
    const double cells = 2.0 * chunk_size_m / o.base_cell_m;
    if (std::abs(cells - std::round(cells)) > 1e-6 * cells)
        return "two chunks of " + std::to_string(chunk_size_m) + " m are not a whole number of group cells of " +
               std::to_string(o.base_cell_m) + " m";
    return {};
}

float group_cell_size(const GroupOptions& o, int depth) {
    return o.base_cell_m * static_cast<float>(1 << (depth - 1));
}

SplatCloud pool_group(std::span<const SplatCloud> members, const glm::vec3& origin, float cell_m, float fill) {
    return pool_group(
        members.size(), [&](std::size_t k) { return members[k]; }, origin, cell_m, fill);
}

SplatCloud pool_group(std::size_t count, const std::function<SplatCloud(std::size_t)>& read_member,
                      const glm::vec3& origin, float cell_m, float fill) {
    GroupPooling pooling{glm::dvec3(origin), static_cast<double>(cell_m)};
    for (std::size_t k = 0; k < count; ++k) pooling.first_pass(read_member(k));
    for (std::size_t k = 0; k < count; ++k) pooling.second_pass(read_member(k));
    return pooling.finish(static_cast<double>(fill));
}

std::string group_generator_settings(const GroupOptions& o) {
    if (!o.enabled) return {};
    std::ostringstream s;
    s << "groups 1; moments pooling of level 1 on a world grid, cell " << o.base_cell_m
      << " m at depth 1, x2 per depth, fill " << o.fill;
    return s.str();
}

namespace {

struct GroupTask {
    int depth = 0;
    glm::ivec2 index{0};
    std::vector<std::size_t> members;  // into the chunk list
};

std::vector<GroupTask> group_tasks(const std::vector<ChunkEntry>& chunks, int count) {
    std::vector<GroupTask> tasks;
    for (int depth = 1; depth <= group_depths(count); ++depth) {
        std::map<std::pair<int, int>, std::vector<std::size_t>> members;  // by (row, column): index order
        for (std::size_t k = 0; k < chunks.size(); ++k) {
            if (chunks[k].span >= depth) continue;  // the chunk is as large as the group: none over it
            const glm::ivec2 g = group_of_chunk(chunks[k].cell, count, depth);
            members[{g.y, g.x}].push_back(k);
        }
        for (auto& [key, list] : members) tasks.push_back({depth, {key.second, key.first}, std::move(list)});
    }
    return tasks;
}

}  // namespace

std::vector<ChunkEntry> build_groups(const fs::path& folder, const fs::path& generation,
                                     const std::vector<ChunkEntry>& chunks, float size_m, float chunk_size_m,
                                     const GroupOptions& options, const StreamLevelRule& rule, ChunkCodec codec,
                                     int threads, const std::function<void(const GroupProgress&)>& progress) {
    if (!options.enabled || chunks.empty()) return {};
    if (const std::string problem = check_group_options(options, chunk_size_m); !problem.empty())
        engine::fail("chunk groups: " + problem);
    const int count = static_cast<int>(std::lround(size_m / chunk_size_m));
    const std::vector<GroupTask> tasks = group_tasks(chunks, count);
    std::vector<ChunkEntry> entries(tasks.size());
    const glm::vec3 origin(-0.5f * size_m, 0.0f, -0.5f * size_m);
    std::error_code ec;
    fs::create_directories(folder / generation / "groups", ec);
    if (ec) engine::fail((folder / generation / "groups").string() + ": cannot create the folder: " + ec.message());
    std::mutex mutex;
    std::size_t done = 0;
    if (progress) progress({1, 0, tasks.size()});
    // Deepest groups are the largest: start them first so that they do not finish last alone.
    std::vector<std::size_t> order(tasks.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = order.size() - 1 - k;
    reference::detail::parallel_for(order.size(), reference::detail::resolve_thread_count(threads), [&](std::size_t n) {
        const GroupTask& task = tasks[order[n]];
        const std::string id = group_id(task.depth, task.index);
        try {
            // Each member is read twice, one at a time (group_pooling.h): a group of the whole world
            // needs the memory of one chunk and its cells' sums, not of the world.
            const auto read_member = [&](std::size_t m) {
                const ChunkEntry& c = chunks[task.members[m]];
                return read_chunk_range(folder / c.file, c, 0, c.prefix_count[0]);
            };
            const SplatCloud pooled = pool_group(task.members.size(), read_member, origin,
                                                 group_cell_size(options, task.depth), options.fill);
            const fs::path file = generation / "groups" / (id + chunk_extension(codec));
            ChunkEntry entry = write_chunk_file(pooled, folder, file, task.index, rule, codec);
            entry.id = id;
            entry.depth = task.depth;
            entry.cell_m = group_cell_size(options, task.depth);
            entries[order[n]] = std::move(entry);
        } catch (const std::exception& e) {
            engine::fail(id + ": " + e.what());
        }
        const std::lock_guard lock(mutex);
        ++done;
        if (progress) progress({task.depth, done, tasks.size()});
    });
    return entries;
}

}  // namespace splat_lod::world
