// Chunk groups (world/world_groups.h): the quadtree over the chunk grid, the pooling of a group's
// members on the world-aligned cell grid, and the build of every group of a world from its chunk files.
#include "splat_lod/worldgen/world_groups.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <sstream>

#include <glm/gtc/quaternion.hpp>

#include "engine/core/error.h"
#include "splat_lod/core/chunk_reader.h"
#include "splat_lod/core/chunk_writer.h"
#include "splat_lod/core/instance_frame.h"
#include "splat_lod/core/parallel_for.h"
#include "splat_lod/core/splat_io.h"
#include "splat_lod/core/splat_math.h"
#include "splat_lod/core/stream_levels.h"

namespace splat_lod::world {
namespace {

namespace fs = std::filesystem;

using reference::detail::sigmoid;

// Mean over the three axis projections of √det of the 2×2 block: how much area the Gaussian covers,
// independent of the view (the weight and the opacity scale of the pooling).
double projected_area(const glm::dmat3& s) {
    const double xy = s[0][0] * s[1][1] - s[1][0] * s[1][0];
    const double xz = s[0][0] * s[2][2] - s[2][0] * s[2][0];
    const double yz = s[1][1] * s[2][2] - s[2][1] * s[2][1];
    return (std::sqrt(std::max(xy, 0.0)) + std::sqrt(std::max(xz, 0.0)) + std::sqrt(std::max(yz, 0.0))) / 3.0;
}

// One drawable level-1 Gaussian of a member, with its cell.
struct Entry {
    std::uint64_t morton = 0;
    glm::i64vec3 cell{0};
    std::uint32_t member = 0, index = 0;
    bool keep = false;  // larger than a cell: kept as it is
};

struct Activated {
    glm::dvec3 mean{0.0};
    glm::dmat3 covariance{0.0};
    double opacity = 0.0;
    double area = 0.0;
};

Activated activate(const SplatCloud& c, std::size_t i) {
    Activated a;
    a.mean = glm::dvec3(c.positions[i]);
    const glm::dvec3 s = glm::exp(glm::dvec3(c.log_scales[i]));
    const glm::dmat3 rs = math::rotation_of(c.rotations[i]) * glm::dmat3(s.x, 0, 0, 0, s.y, 0, 0, 0, s.z);
    a.covariance = rs * glm::transpose(rs);
    a.opacity = sigmoid(c.opacity_logits[i]);
    a.area = std::max(projected_area(a.covariance), 1e-30);
    return a;
}

bool drawable(const SplatCloud& c, std::size_t i) {
    const glm::vec3& p = c.positions[i];
    const glm::vec3& s = c.log_scales[i];
    const Rotation& q = c.rotations[i];
    const float sum = p.x + p.y + p.z + s.x + s.y + s.z + c.opacity_logits[i] + q.w + q.x + q.y + q.z;
    if (!std::isfinite(sum) || q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z == 0.0f) return false;
    return sigmoid(c.opacity_logits[i]) > 1.0 / 255.0;
}

void copy_gaussian(const SplatCloud& from, std::size_t i, SplatCloud& to, std::size_t out) {
    to.positions[out] = from.positions[i];
    to.rotations[out] = from.rotations[i];
    to.log_scales[out] = from.log_scales[i];
    to.opacity_logits[out] = from.opacity_logits[i];
    to.sh_dc[out] = from.sh_dc[i];
    const std::size_t from_stride = from.sh_rest_stride(), to_stride = to.sh_rest_stride();
    for (std::size_t k = 0; k < std::min(from_stride, to_stride); ++k)
        to.sh_rest[out * to_stride + k] = from.sh_rest[i * from_stride + k];
}

// The moment-matched Gaussian of one cell's members (see world_groups.h), written at `out`.
void pool_cell(std::span<const SplatCloud> members, std::span<const Entry> cell, double cell_m, double fill,
               SplatCloud& to, std::size_t out) {
    std::vector<Activated> a(cell.size());
    double total = 0.0;
    glm::dvec3 mean(0.0);
    for (std::size_t k = 0; k < cell.size(); ++k) {
        a[k] = activate(members[cell[k].member], cell[k].index);
        const double w = a[k].opacity * a[k].area;
        total += w;
        mean += w * a[k].mean;
    }
    mean /= total;
    glm::dmat3 covariance(0.0);
    const std::size_t stride = to.sh_rest_stride();
    glm::dvec3 dc(0.0);
    std::vector<double> rest(stride, 0.0);
    for (std::size_t k = 0; k < cell.size(); ++k) {
        const double w = a[k].opacity * a[k].area / total;
        const glm::dvec3 d = a[k].mean - mean;
        covariance += w * (a[k].covariance + glm::outerProduct(d, d));
        const SplatCloud& m = members[cell[k].member];
        const std::size_t i = cell[k].index, member_stride = m.sh_rest_stride();
        dc += w * glm::dvec3(m.sh_dc[i]);
        for (std::size_t j = 0; j < std::min(stride, member_stride); ++j)
            rest[j] += w * m.sh_rest[i * member_stride + j];
    }
    glm::dvec3 values;
    glm::dmat3 vectors;
    math::symmetric_eigen(covariance, values, vectors);
    if (glm::determinant(vectors) < 0.0) vectors[2] = -vectors[2];
    for (int axis = 0; axis < 3; ++axis)
        if (values[axis] > 0.01 * cell_m * cell_m) values[axis] *= fill * fill;
    const glm::dmat3 widened =
        vectors * glm::dmat3(values.x, 0, 0, 0, values.y, 0, 0, 0, values.z) * glm::transpose(vectors);
    const double area = std::max(projected_area(widened), 1e-30);
    double log_transmittance = 0.0;
    for (const Activated& m : a) log_transmittance += std::log1p(-std::min(0.99, m.opacity * m.area / area));
    const double opacity = std::clamp(1.0 - std::exp(log_transmittance), 1.01 / 255.0, 0.99);

    const glm::dquat q = glm::normalize(glm::quat_cast(vectors));
    to.positions[out] = glm::vec3(mean);
    to.rotations[out] = {static_cast<float>(q.w), static_cast<float>(q.x), static_cast<float>(q.y),
                         static_cast<float>(q.z)};
    for (int axis = 0; axis < 3; ++axis)
        to.log_scales[out][axis] = static_cast<float>(0.5 * std::log(std::max(values[axis], 1e-30)));
    to.opacity_logits[out] = static_cast<float>(std::log(opacity / (1.0 - opacity)));
    to.sh_dc[out] = glm::vec3(dc);
    for (std::size_t j = 0; j < stride; ++j) to.sh_rest[out * stride + j] = static_cast<float>(rest[j]);
}

std::vector<Entry> cell_entries(std::span<const SplatCloud> members, const glm::dvec3& origin, double cell_m) {
    std::vector<Entry> entries;
    for (std::size_t m = 0; m < members.size(); ++m) {
        const SplatCloud& c = members[m];
        for (std::size_t i = 0; i < c.size(); ++i) {
            if (c.lod_level[i] != 1 || !drawable(c, i)) continue;
            Entry e;
            e.member = static_cast<std::uint32_t>(m);
            e.index = static_cast<std::uint32_t>(i);
            const glm::dvec3 p = (glm::dvec3(c.positions[i]) - origin) / cell_m;
            e.cell = glm::i64vec3(glm::floor(p));
            const glm::vec3& s = c.log_scales[i];
            e.keep = std::exp(static_cast<double>(std::max({s.x, s.y, s.z}))) >= cell_m;
            entries.push_back(e);
        }
    }
    if (entries.empty()) return entries;
    glm::i64vec3 low = entries.front().cell;
    for (const Entry& e : entries) low = glm::min(low, e.cell);
    for (Entry& e : entries) {
        const glm::u64vec3 d(e.cell - low);
        e.morton = math::spread_bits(d.x) | math::spread_bits(d.y) << 1 | math::spread_bits(d.z) << 2;
    }
    // Cells in Morton order, a cell's kept Gaussians after its pooled one, members in file order.
    std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
        if (a.cell != b.cell) {
            if (a.morton != b.morton) return a.morton < b.morton;
            return std::tie(a.cell.x, a.cell.y, a.cell.z) < std::tie(b.cell.x, b.cell.y, b.cell.z);
        }
        return a.keep < b.keep;
    });
    return entries;
}

}  // namespace

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
    int degree = 0;
    for (const SplatCloud& m : members) degree = std::max(degree, m.sh_degree);
    const std::vector<Entry> entries = cell_entries(members, glm::dvec3(origin), static_cast<double>(cell_m));
    // Output slots: one per cell with pooled members, one per kept Gaussian.
    // A cell's entries [begin, end): its pooled members [begin, kept), then the ones kept as they are.
    struct Run {
        std::size_t begin, kept, end;
    };
    std::vector<Run> runs;
    std::size_t outputs = 0;
    for (std::size_t b = 0; b < entries.size();) {
        Run run{b, b, b};
        while (run.end < entries.size() && entries[run.end].cell == entries[b].cell) ++run.end;
        while (run.kept < run.end && !entries[run.kept].keep) ++run.kept;
        outputs += (run.kept > run.begin ? 1 : 0) + (run.end - run.kept);
        runs.push_back(run);
        b = run.end;
    }
    SplatCloud out;
    out.set_sh_degree(degree);
    out.resize(outputs);
    std::size_t next = 0;
    for (const Run& run : runs) {
        if (run.kept > run.begin)
            pool_cell(members, std::span<const Entry>(entries.data() + run.begin, run.kept - run.begin), cell_m, fill,
                      out, next++);
        for (std::size_t k = run.kept; k < run.end; ++k)
            copy_gaussian(members[entries[k].member], entries[k].index, out, next++);
    }
    std::fill(out.lod_level.begin(), out.lod_level.end(), std::uint8_t{4});
    std::fill(out.coverage_min.begin(), out.coverage_min.end(), -1.0f);
    std::fill(out.coverage_max.begin(), out.coverage_max.end(), -1.0f);
    return out;
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
            std::vector<SplatCloud> members;
            members.reserve(task.members.size());
            for (const std::size_t k : task.members)
                members.push_back(read_chunk_range(folder / chunks[k].file, chunks[k], 0, chunks[k].prefix_count[0]));
            SplatCloud pooled = pool_group(members, origin, group_cell_size(options, task.depth), options.fill);
            members.clear();
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
