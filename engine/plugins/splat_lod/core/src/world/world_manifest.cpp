// world.json: reading with a check of every value, and the atomic writer (world/world_manifest.h).
//   { "version": 5, "seed": 7, "size_m": 1024, "chunk_size_m": 64, "feature_m": 1024 (left out when equal to size_m),
//     "up": [0, 1, 0],
//     "gaussians": 10400000, "density": 1, "generator": "…",
//     "stream_levels": { "size_threshold_px": 2, "rel_min": 0.5, "reach_min": [0.4, 0.12, 0.04] },
//     "chunks": [ { "id": "chunk_-008_-008", "file": "gen-1/chunks/chunk_-008_-008.lod.ply", "cell": [-8, -8],
//                   "bounds_min": [x, y, z], "bounds_max": [x, y, z], "prefix_count": [n1, n2, n3, n4],
//                   "levels": [ { "extent_max": e, "extent_per_min_coverage_max": r } × 4 ],
//                   "codec": "compact" (left out for "ply"), "header_bytes": h, "vertex_bytes": v,
//                   "file_bytes": f,
//                   "header_crc32": c, "record_crc32": [c0, c1, …] } … ],
//     "props": [ { "mesh": "gen-1/meshes/house.glb", "translation": [x, y, z], "rotation_euler_deg": [0, yaw, 0],
//                  "scale": [1, 1, 1] } … ],
//     "terrain_mesh": "gen-1/meshes/terrain.glb",
//     "groups": [ { …the keys of a chunk…, "depth": 1, "cell_m": 0.5 } … ], "group_generator": "…" }
// File paths are relative to the manifest's folder; the generator puts each run's files in its own
// gen-<n>/ folder (world_generator.h: output safety), worlds of earlier versions have chunks/ and
// meshes/ beside world.json. Both read the same way. The reader is strict (unknown keys are errors,
// so a typo never passes as a default); "feature_m", "up", "density", "generator", "props" and
// "terrain_mesh" may be left out.
#include "splat_lod/core/world_manifest.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <tuple>
#include <utility>

#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "io/io_util.h"
#include "splat_lod/core/chunk_quadtree.h"
#include "world_manifest_extras.h"

namespace splat_lod::world {
namespace {

using nlohmann::json;

// Reads one manifest document; every error is "<file>: <key path>: <problem>".
class ManifestReader {
public:
    explicit ManifestReader(std::string file) : file_(std::move(file)) {}

    [[noreturn]] void error(const std::string& key, const std::string& problem) const {
        engine::fail(file_ + ": " + (key.empty() ? "" : key + ": ") + problem);
    }

    void only_keys(const json& object, const std::string& key, std::initializer_list<const char*> allowed) const {
        if (!object.is_object()) error(key, "expected an object, got " + object.dump());
        for (const auto& item : object.items()) {
            bool known = false;
            for (const char* name : allowed) known = known || item.key() == name;
            if (!known) error(join(key, item.key()), "unknown key");
        }
    }

    const json& member(const json& object, const std::string& key, const char* name) const {
        const auto it = object.find(name);
        if (it == object.end()) error(join(key, name), "missing (required)");
        return *it;
    }

    std::uint64_t whole(const json& value, const std::string& key) const {
        // Parsed text gives unsigned numbers; values built in code (the writer's check) may be signed.
        if (value.is_number_unsigned()) return value.get<std::uint64_t>();
        if (value.is_number_integer() && value.get<std::int64_t>() >= 0)
            return static_cast<std::uint64_t>(value.get<std::int64_t>());
        error(key, "expected a whole number >= 0, got " + value.dump());
    }

    int signed_int(const json& value, const std::string& key) const {
        if (!value.is_number_integer()) error(key, "expected a whole number, got " + value.dump());
        const auto v = value.get<std::int64_t>();
        if (v < -(1 << 30) || v > (1 << 30)) error(key, "out of range: " + value.dump());
        return static_cast<int>(v);
    }

    std::uint32_t crc32(const json& value, const std::string& key) const {
        const std::uint64_t v = whole(value, key);
        if (v > 0xffffffffu) error(key, "expected a CRC-32 (0 to 4294967295), got " + value.dump());
        return static_cast<std::uint32_t>(v);
    }

    float number(const json& value, const std::string& key) const {
        if (!value.is_number()) error(key, "expected a number, got " + value.dump());
        const double v = value.get<double>();
        if (!std::isfinite(v) || std::abs(v) > 3.0e38) error(key, "expected a finite number, got " + value.dump());
        return static_cast<float>(v);
    }

    float positive(const json& value, const std::string& key) const {
        const float v = number(value, key);
        if (!(v > 0.0f)) error(key, "must be positive, got " + value.dump());
        return v;
    }

    float non_negative(const json& value, const std::string& key) const {
        const float v = number(value, key);
        if (v < 0.0f) error(key, "must not be negative, got " + value.dump());
        return v;
    }

    glm::vec3 vec3(const json& value, const std::string& key) const {
        if (!value.is_array() || value.size() != 3) error(key, "expected an array of 3 numbers, got " + value.dump());
        glm::vec3 v;
        for (int i = 0; i < 3; ++i) v[i] = number(value[static_cast<std::size_t>(i)], index(key, i));
        return v;
    }

    std::string text(const json& value, const std::string& key) const {
        if (!value.is_string()) error(key, "expected a string, got " + value.dump());
        return value.get<std::string>();
    }

    // A path below the manifest's folder: relative, without "..", so that a manifest can never
    // make a reader open a file elsewhere.
    std::filesystem::path relative_path(const json& value, const std::string& key, bool allow_empty) const {
        const std::filesystem::path path(text(value, key));
        if (path.empty()) {
            if (!allow_empty) error(key, "must not be empty");
            return path;
        }
        if (!io::stays_below_folder(path))
            error(key, "\"" + path.string() + "\" " +
                           (path.is_relative() && !path.has_root_name() ? "leaves the manifest's folder"
                                                                        : "must be relative to the manifest's folder"));
        return path;
    }

    static std::string join(const std::string& key, const std::string& name) {
        return key.empty() ? name : key + "." + name;
    }
    static std::string index(const std::string& key, std::size_t i) { return key + "[" + std::to_string(i) + "]"; }

    WorldManifest manifest(const json& document) const;

private:
    ChunkEntry chunk(const json& object, const std::string& key, bool group) const;
    // The entry's file: codec, byte counts and checksums (after its prefix counts).
    void chunk_file(const json& object, const std::string& key, ChunkEntry& c) const;
    void chunks(const json& list, WorldManifest& m) const;
    void groups(const json& list, WorldManifest& m) const;
    ChunkLevel level(const json& object, const std::string& key) const;
    StreamLevelRule stream_level_rule(const json& object, const std::string& key) const;
    Prop prop(const json& object, const std::string& key) const;
    void check_chunk_counts(const ChunkEntry& c, const std::string& key) const;

    std::string file_;
};

ChunkLevel ManifestReader::level(const json& object, const std::string& key) const {
    only_keys(object, key, {"extent_max", "extent_per_min_coverage_max"});
    ChunkLevel l;
    l.extent_max = non_negative(member(object, key, "extent_max"), join(key, "extent_max"));
    const std::string ratio_key = join(key, "extent_per_min_coverage_max");
    l.extent_per_min_coverage_max = number(member(object, key, "extent_per_min_coverage_max"), ratio_key);
    if (l.extent_per_min_coverage_max < 0.0f && l.extent_per_min_coverage_max != -1.0f)
        error(ratio_key, "must be -1 (always needed) or not negative");
    return l;
}

void ManifestReader::check_chunk_counts(const ChunkEntry& c, const std::string& key) const {
    for (int l = 1; l < kLevels; ++l)
        if (c.prefix_count[static_cast<std::size_t>(l)] > c.prefix_count[static_cast<std::size_t>(l - 1)])
            error(join(key, "prefix_count"),
                  "counts must not increase with the stream level (Gaussians with stream level >= " +
                      std::to_string(l + 1) + " are a prefix of those with stream level >= " + std::to_string(l) + ")");
    if (c.codec == ChunkCodec::compact) {
        // The block sizes are in the file's header: the reader checks they add up to file_bytes.
        if (c.vertex_bytes != 0) error(join(key, "vertex_bytes"), "must be 0 for a compressed chunk");
        if (c.file_bytes < c.header_bytes) error(join(key, "file_bytes"), "is less than header_bytes");
        return;
    }
    if (c.vertex_bytes == 0) error(join(key, "vertex_bytes"), "must be positive");
    // file_bytes = header_bytes + prefix_count[0] · vertex_bytes, checked without overflow.
    std::uint64_t records = 0, total = 0;
    if (__builtin_mul_overflow(c.prefix_count[0], c.vertex_bytes, &records) ||
        __builtin_add_overflow(records, c.header_bytes, &total) || total != c.file_bytes)
        error(join(key, "file_bytes"), std::to_string(c.file_bytes) +
                                           " differs from header_bytes + prefix_count[0] x "
                                           "vertex_bytes");
}

ChunkEntry ManifestReader::chunk(const json& object, const std::string& key, bool group) const {
    if (group)
        only_keys(object, key,
                  {"id", "file", "cell", "bounds_min", "bounds_max", "prefix_count", "levels", "codec", "header_bytes",
                   "vertex_bytes", "file_bytes", "header_crc32", "record_crc32", "depth", "cell_m"});
    else
        only_keys(object, key,
                  {"id", "file", "cell", "span", "bounds_min", "bounds_max", "prefix_count", "levels", "codec",
                   "header_bytes", "vertex_bytes", "file_bytes", "header_crc32", "record_crc32"});
    ChunkEntry c;
    if (!group && object.contains("span")) {
        const std::uint64_t span = whole(object["span"], join(key, "span"));
        if (span > 10) error(join(key, "span"), "must be 0 to 10");
        c.span = static_cast<int>(span);
    }
    if (group) {
        const std::uint64_t depth = whole(member(object, key, "depth"), join(key, "depth"));
        if (depth < 1 || depth > 30) error(join(key, "depth"), "must be 1 to 30");
        c.depth = static_cast<int>(depth);
        c.cell_m = positive(member(object, key, "cell_m"), join(key, "cell_m"));
    }
    c.id = text(member(object, key, "id"), join(key, "id"));
    if (c.id.empty()) error(join(key, "id"), "must not be empty");
    c.file = relative_path(member(object, key, "file"), join(key, "file"), false);
    const json& cell = member(object, key, "cell");
    if (!cell.is_array() || cell.size() != 2) error(join(key, "cell"), "expected [column, row], got " + cell.dump());
    c.cell = {signed_int(cell[0], index(join(key, "cell"), 0)), signed_int(cell[1], index(join(key, "cell"), 1))};
    c.bounds_min = vec3(member(object, key, "bounds_min"), join(key, "bounds_min"));
    c.bounds_max = vec3(member(object, key, "bounds_max"), join(key, "bounds_max"));
    for (int i = 0; i < 3; ++i)
        if (c.bounds_min[i] > c.bounds_max[i]) error(join(key, "bounds_min"), "is above bounds_max");
    const json& counts = member(object, key, "prefix_count");
    const json& levels = member(object, key, "levels");
    if (!counts.is_array() || counts.size() != kLevels)
        error(join(key, "prefix_count"), "expected an array of 4 counts, got " + counts.dump());
    if (!levels.is_array() || levels.size() != kLevels)
        error(join(key, "levels"), "expected an array of 4 objects, got " + levels.dump());
    for (std::size_t l = 0; l < kLevels; ++l) {
        c.prefix_count[l] = whole(counts[l], index(join(key, "prefix_count"), l));
        c.levels[l] = level(levels[l], index(join(key, "levels"), l));
    }
    chunk_file(object, key, c);
    return c;
}

void ManifestReader::chunk_file(const json& object, const std::string& key, ChunkEntry& c) const {
    if (object.contains("codec")) {
        const std::string codec = text(object["codec"], join(key, "codec"));
        if (codec != "ply" && codec != "compact")
            error(join(key, "codec"), "expected \"ply\" or \"compact\", got \"" + codec + "\"");
        c.codec = codec == "compact" ? ChunkCodec::compact : ChunkCodec::ply;
    }
    c.header_bytes = whole(member(object, key, "header_bytes"), join(key, "header_bytes"));
    c.vertex_bytes = whole(member(object, key, "vertex_bytes"), join(key, "vertex_bytes"));
    c.file_bytes = whole(member(object, key, "file_bytes"), join(key, "file_bytes"));
    check_chunk_counts(c, key);
    c.header_crc32 = crc32(member(object, key, "header_crc32"), join(key, "header_crc32"));
    const std::string blocks_key = join(key, "record_crc32");
    const json& blocks = member(object, key, "record_crc32");
    if (!blocks.is_array()) error(blocks_key, "expected an array of CRC-32 values, got " + blocks.dump());
    const std::uint64_t expected = record_block_count(c);
    if (blocks.size() != expected)
        error(blocks_key, "holds " + std::to_string(blocks.size()) + " checksums, the prefix counts make " +
                              std::to_string(expected) + " blocks of up to " + std::to_string(c.block_records()) +
                              " records");
    c.record_crc32.reserve(blocks.size());
    for (std::size_t b = 0; b < blocks.size(); ++b) c.record_crc32.push_back(crc32(blocks[b], index(blocks_key, b)));
}

Prop ManifestReader::prop(const json& object, const std::string& key) const {
    only_keys(object, key, {"mesh", "translation", "rotation_euler_deg", "scale"});
    Prop p;
    p.mesh = relative_path(member(object, key, "mesh"), join(key, "mesh"), false);
    p.translation = vec3(member(object, key, "translation"), join(key, "translation"));
    p.rotation_euler_deg = vec3(member(object, key, "rotation_euler_deg"), join(key, "rotation_euler_deg"));
    p.scale = vec3(member(object, key, "scale"), join(key, "scale"));
    for (int i = 0; i < 3; ++i)
        if (!(p.scale[i] > 0.0f)) error(join(key, "scale"), "every component must be positive");
    return p;
}

StreamLevelRule ManifestReader::stream_level_rule(const json& object, const std::string& key) const {
    only_keys(object, key, {"size_threshold_px", "rel_min", "reach_min"});
    StreamLevelRule rule;
    rule.lod.size_threshold_px = positive(member(object, key, "size_threshold_px"), join(key, "size_threshold_px"));
    rule.lod.rel_min = positive(member(object, key, "rel_min"), join(key, "rel_min"));
    const json& reach = member(object, key, "reach_min");
    if (!reach.is_array() || reach.size() != rule.reach_min.size())
        error(join(key, "reach_min"), "expected an array of 3 reaches, got " + reach.dump());
    for (std::size_t k = 0; k < rule.reach_min.size(); ++k)
        rule.reach_min[k] = positive(reach[k], index(join(key, "reach_min"), k));
    if (const std::string problem = check_stream_level_rule(rule); !problem.empty()) error(key, problem);
    return rule;
}

// The grid cells the chunks claim: a chunk of span s > 0 must be aligned to 2^s, lie inside the grid,
// and share no cell with another chunk (cells of span 0 are only checked against those).
class GridCover {
public:
    GridCover(const ManifestReader& reader, int count) : reader_(reader), count_(count) {}

    void claim(const ChunkEntry& c, const std::string& key) {
        if (c.span == 0) {
            if (spanned_.count({c.cell.x, c.cell.y}) != 0) overlap(key);
            single_.insert({c.cell.x, c.cell.y});
            return;
        }
        const int side = 1 << c.span;
        const glm::ivec2 i = c.cell + glm::ivec2(count_ / 2);
        if (i.x < 0 || i.y < 0 || i.x % side != 0 || i.y % side != 0 || i.x + side > count_ || i.y + side > count_)
            reader_.error(ManifestReader::join(key, "cell"), "a chunk of span " + std::to_string(c.span) +
                                                                 " must start at a multiple of " +
                                                                 std::to_string(side) + " cells and lie inside the " +
                                                                 std::to_string(count_) + "-cell grid");
        for (int z = 0; z < side; ++z)
            for (int x = 0; x < side; ++x) {
                const std::pair<int, int> cell{c.cell.x + x, c.cell.y + z};
                if (single_.count(cell) != 0 || !spanned_.insert(cell).second) overlap(key);
            }
    }

private:
    [[noreturn]] void overlap(const std::string& key) const {
        reader_.error(ManifestReader::join(key, "cell"), "overlaps an earlier chunk");
    }

    const ManifestReader& reader_;
    int count_;
    std::set<std::pair<int, int>> single_, spanned_;
};

WorldManifest ManifestReader::manifest(const json& document) const {
    if (!document.is_object()) error("", "expected a JSON object at the top level");
    WorldManifest m;
    // The version first: another version may well have other keys, and saying so is more useful.
    const std::uint64_t version = whole(member(document, "", "version"), "version");
    if (version < static_cast<std::uint64_t>(kOldestManifestVersion) ||
        version > static_cast<std::uint64_t>(kManifestVersion))
        error("version", "expected " + std::to_string(kOldestManifestVersion) + " to " +
                             std::to_string(kManifestVersion) + ", got " + std::to_string(version) +
                             " (written by another version of the generator: generate the world again)");
    if (version >= 4)
        only_keys(
            document, "",
            {"version", "seed", "size_m", "chunk_size_m", "feature_m", "up", "gaussians", "density", "generator",
             "stream_levels", "chunks", "props", "terrain_mesh", "groups", "group_generator", "ground", "capture"});
    else
        only_keys(document, "",
                  {"version", "seed", "size_m", "chunk_size_m", "up", "gaussians", "density", "generator",
                   "stream_levels", "chunks", "props", "terrain_mesh"});
    m.version = static_cast<int>(version);
    m.seed = whole(member(document, "", "seed"), "seed");
    m.size_m = positive(member(document, "", "size_m"), "size_m");
    m.chunk_size_m = positive(member(document, "", "chunk_size_m"), "chunk_size_m");
    if (m.chunk_size_m > m.size_m) error("chunk_size_m", "is larger than size_m");
    if (document.contains("feature_m")) {
        m.feature_m = positive(document["feature_m"], "feature_m");
        if (m.feature_m > m.size_m) error("feature_m", "is larger than size_m");
    }
    if (document.contains("up")) m.up = vec3(document["up"], "up");
    if (!(glm::length(m.up) > 0.0f)) error("up", "must not be the zero vector");
    m.gaussians = whole(member(document, "", "gaussians"), "gaussians");
    if (document.contains("density")) m.density = positive(document["density"], "density");
    if (document.contains("generator")) m.generator = text(document["generator"], "generator");
    m.stream_levels = stream_level_rule(member(document, "", "stream_levels"), "stream_levels");
    if (document.contains("terrain_mesh"))
        m.terrain_mesh = relative_path(document["terrain_mesh"], "terrain_mesh", true);

    chunks(member(document, "", "chunks"), m);
    if (document.contains("groups")) groups(document["groups"], m);
    if (document.contains("group_generator")) m.group_generator = text(document["group_generator"], "group_generator");
    if (document.contains("ground")) m.ground = parse_ground_grid(document["ground"], file_);
    if (document.contains("capture")) m.capture = parse_capture_origin(document["capture"], file_);
    if (document.contains("props")) {
        const json& props = document["props"];
        if (!props.is_array()) error("props", "expected an array");
        for (std::size_t i = 0; i < props.size(); ++i) m.props.push_back(prop(props[i], index("props", i)));
    }
    return m;
}

// The chunk list: ids and cells unique, the cells of chunks of several cells apart, and the counts
// summing to the manifest's `gaussians`.
void ManifestReader::chunks(const json& list, WorldManifest& m) const {
    if (!list.is_array()) error("chunks", "expected an array");
    std::set<std::string> ids;
    std::set<std::pair<int, int>> cells;
    GridCover covered(*this, chunks_per_side(m));
    std::uint64_t total = 0;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string key = index("chunks", i);
        m.chunks.push_back(chunk(list[i], key, false));
        const ChunkEntry& c = m.chunks.back();
        if (!ids.insert(c.id).second) error(join(key, "id"), "\"" + c.id + "\" is used by an earlier chunk");
        if (!cells.insert({c.cell.x, c.cell.y}).second) error(join(key, "cell"), "is used by an earlier chunk");
        covered.claim(c, key);
        if (__builtin_add_overflow(total, c.prefix_count[0], &total)) error("gaussians", "the chunks' sum overflows");
    }
    if (total != m.gaussians)
        error("gaussians", std::to_string(m.gaussians) + " but the chunks hold " + std::to_string(total));
}

void ManifestReader::groups(const json& list, WorldManifest& m) const {
    if (!list.is_array()) error("groups", "expected an array");
    std::set<std::string> ids;
    for (const ChunkEntry& c : m.chunks) ids.insert(c.id);
    std::set<std::tuple<int, int, int>> cells;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string key = index("groups", i);
        m.groups.push_back(chunk(list[i], key, true));
        const ChunkEntry& g = m.groups.back();
        if (!ids.insert(g.id).second) error(join(key, "id"), "\"" + g.id + "\" is used by an earlier chunk or group");
        if (!cells.insert({g.depth, g.cell.x, g.cell.y}).second)
            error(join(key, "cell"), "is used by an earlier group of the same depth");
        for (int l = 1; l < kLevels; ++l)
            if (g.prefix_count[static_cast<std::size_t>(l)] != g.prefix_count[0])
                error(join(key, "prefix_count"),
                      "a group's Gaussians are all of stream level 4: the counts must be equal");
    }
}

json vec3_json(const glm::vec3& v) {
    return json::array({v.x, v.y, v.z});
}

json chunk_json(const ChunkEntry& c) {
    json levels = json::array();
    for (const ChunkLevel& l : c.levels)
        levels.push_back(
            {{"extent_max", l.extent_max}, {"extent_per_min_coverage_max", l.extent_per_min_coverage_max}});
    json entry = {{"id", c.id},
                  {"file", c.file.generic_string()},
                  {"cell", json::array({c.cell.x, c.cell.y})},
                  {"bounds_min", vec3_json(c.bounds_min)},
                  {"bounds_max", vec3_json(c.bounds_max)},
                  {"prefix_count", c.prefix_count},
                  {"levels", levels},
                  {"header_bytes", c.header_bytes},
                  {"vertex_bytes", c.vertex_bytes},
                  {"file_bytes", c.file_bytes},
                  {"header_crc32", c.header_crc32},
                  {"record_crc32", c.record_crc32}};
    if (c.span > 0) entry["span"] = c.span;  // absent for one cell: generated worlds keep their bytes
    if (c.codec == ChunkCodec::compact) entry["codec"] = "compact";  // absent for PLY chunks, likewise
    return entry;
}

json manifest_json(const WorldManifest& m) {
    json chunks = json::array(), props = json::array(), groups = json::array();
    for (const ChunkEntry& c : m.chunks) chunks.push_back(chunk_json(c));
    for (const ChunkEntry& g : m.groups) {
        json entry = chunk_json(g);
        entry["depth"] = g.depth;
        entry["cell_m"] = g.cell_m;
        groups.push_back(std::move(entry));
    }
    for (const Prop& p : m.props)
        props.push_back({{"mesh", p.mesh.generic_string()},
                         {"translation", vec3_json(p.translation)},
                         {"rotation_euler_deg", vec3_json(p.rotation_euler_deg)},
                         {"scale", vec3_json(p.scale)}});
    json out = {{"version", m.version},
                {"seed", m.seed},
                {"size_m", m.size_m},
                {"chunk_size_m", m.chunk_size_m},
                {"up", vec3_json(m.up)},
                {"gaussians", m.gaussians},
                {"density", m.density},
                {"generator", m.generator},
                {"stream_levels",
                 {{"size_threshold_px", m.stream_levels.lod.size_threshold_px},
                  {"rel_min", m.stream_levels.lod.rel_min},
                  {"reach_min", m.stream_levels.reach_min}}},
                {"chunks", chunks},
                {"props", props},
                {"terrain_mesh", m.terrain_mesh.generic_string()},
                {"groups", groups},
                {"group_generator", m.group_generator}};
    if (m.feature_scale() != m.size_m) out["feature_m"] = m.feature_scale();
    if (!m.ground.empty()) out["ground"] = ground_grid_json(m.ground);
    if (!m.capture.empty()) out["capture"] = capture_origin_json(m.capture);
    return out;
}

}  // namespace

std::string chunk_id(const glm::ivec2& cell) {
    char text[48];
    std::snprintf(text, sizeof text, "chunk_%+04d_%+04d", cell.x, cell.y);
    return text;
}

std::uint32_t chunks_checksum(const WorldManifest& manifest) {
    json document = manifest_json(manifest);
    for (const char* key : {"version", "groups", "group_generator"}) document.erase(key);
    const std::string text = document.dump();
    return checksum(std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

WorldManifest read_world_manifest(const std::filesystem::path& path) {
    return parse_world_manifest(engine::read_text_file(path), path.string());
}

WorldManifest parse_world_manifest(const std::string& text, const std::string& name) {
    const ManifestReader reader(name);
    json document;
    try {
        document = json::parse(text);
    } catch (const json::exception& e) {
        reader.error("", std::string("invalid JSON: ") + e.what());
    }
    return reader.manifest(document);
}

void write_world_manifest(const std::filesystem::path& path, const WorldManifest& manifest) {
    if (manifest.version < kOldestManifestVersion || manifest.version > kManifestVersion)
        engine::fail(path.string() + ": version: this program writes version " + std::to_string(kManifestVersion) +
                     " (and reads " + std::to_string(kOldestManifestVersion) + " to " +
                     std::to_string(kManifestVersion) + ")");
    // A version-3 manifest is a version-4 one without groups, a version-4 one a version-5 one whose
    // chunks are all PLY files: always written as the newest.
    json document = manifest_json(manifest);
    document["version"] = kManifestVersion;
    // The reader's rules, applied before anything is written: a manifest this writer accepts
    // always reads back.
    ManifestReader(path.string()).manifest(document);
    engine::write_text_file_atomic(path, document.dump(1) + "\n");
}

}  // namespace splat_lod::world
