// Streamed SOG (lod-meta.json): the tree's leaves gathered into per-level, per-file ranges, and the
// ranges read one chunk file at a time (streamed_sog.h).
#include "splat_lod/core/streamed_sog.h"

#include <algorithm>
#include <map>

#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "io_util.h"
#include "readers.h"
#include "splat_lod/core/splat_io.h"

namespace splat_lod::io {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Bounds that no real file reaches; they keep hostile files from recursing or allocating without end.
constexpr int kMaxTreeDepth = 64;
constexpr int kMaxLevels = 64;
constexpr const char* kMetaName = "lod-meta.json";

[[noreturn]] void meta_error(const fs::path& path, const std::string& problem) {
    fail_file(path.string(), problem);
}

fs::path meta_file_of(const fs::path& path) {
    std::error_code ec;
    return fs::is_directory(path, ec) ? path / kMetaName : path;
}

json parse_document(const fs::path& path) {
    const std::string text = engine::read_text_file(path);
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::parse_error& e) {
        meta_error(path, std::string("not valid JSON: ") + e.what());
    }
    if (!doc.is_object()) meta_error(path, "expected a JSON object (a lod-meta.json)");
    return doc;
}

std::vector<std::string> read_filenames(const json& doc, const fs::path& path) {
    if (!doc.contains("filenames")) meta_error(path, "missing \"filenames\"");
    const json& names = doc["filenames"];
    if (!names.is_array() || names.empty()) meta_error(path, "\"filenames\" must be a non-empty array of file names");
    std::vector<std::string> out;
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (!names[i].is_string() || names[i].get<std::string>().empty())
            meta_error(path, "\"filenames\"[" + std::to_string(i) + "] must be a non-empty string");
        // Chunk files lie below the folder of lod-meta.json: a hostile file cannot point elsewhere.
        const fs::path name(names[i].get<std::string>());
        if (!io::stays_below_folder(name))
            meta_error(path, "\"filenames\"[" + std::to_string(i) + "] \"" + name.string() +
                                 "\" leaves the folder of lod-meta.json");
        out.push_back(names[i].get<std::string>());
    }
    return out;
}

// A node of the tree with "lods", and where it is ("tree.children[1]") for messages.
struct Leaf {
    const json* lods;
    std::string where;
};

void collect_leaves(const json& node, const std::string& where, int depth, const fs::path& path,
                    std::vector<Leaf>& leaves) {
    if (!node.is_object()) meta_error(path, where + " must be an object");
    if (depth > kMaxTreeDepth)
        meta_error(path, where + ": the tree is nested deeper than " + std::to_string(kMaxTreeDepth));
    if (node.contains("lods")) {
        if (!node["lods"].is_object()) meta_error(path, where + ".lods must be an object");
        leaves.push_back({&node["lods"], where});
    }
    if (node.contains("children")) {
        const json& children = node["children"];
        if (!children.is_array()) meta_error(path, where + ".children must be an array");
        for (std::size_t i = 0; i < children.size(); ++i)
            collect_leaves(children[i], where + ".children[" + std::to_string(i) + "]", depth + 1, path, leaves);
    }
}

int parse_level_key(const std::string& key, const std::string& where, const fs::path& path) {
    const bool digits = !key.empty() && key.size() <= 2 && key.find_first_not_of("0123456789") == std::string::npos;
    const int level = digits ? std::stoi(key) : -1;
    if (level < 0 || level >= kMaxLevels) meta_error(path, where + ".lods: \"" + key + "\" is not a level number");
    return level;
}

// "lodLevels" when given, else one more than the highest level any leaf lists.
int level_count(const json& doc, const std::vector<Leaf>& leaves, const fs::path& path) {
    if (doc.contains("lodLevels")) {
        const json& n = doc["lodLevels"];
        if (!n.is_number_integer() || n.get<long long>() < 1 || n.get<long long>() > kMaxLevels)
            meta_error(path, "\"lodLevels\" must be an integer from 1 to " + std::to_string(kMaxLevels));
        return n.get<int>();
    }
    int count = 0;
    for (const Leaf& leaf : leaves)
        for (const auto& item : leaf.lods->items())
            count = std::max(count, parse_level_key(item.key(), leaf.where, path) + 1);
    if (count == 0) meta_error(path, "the tree lists no level");
    return count;
}

std::uint64_t nonnegative(const json& entry, const char* key, const std::string& where, const fs::path& path) {
    if (!entry.contains(key)) meta_error(path, where + ": missing \"" + key + "\"");
    const json& v = entry[key];
    if (!v.is_number_integer() || v.get<long long>() < 0)
        meta_error(path, where + ": \"" + key + "\" must be a non-negative integer");
    return v.get<std::uint64_t>();
}

// Sorts each file's ranges and refuses overlaps (the same Gaussians twice in the scene).
void check_ranges(StreamedSogFile& file, const fs::path& path, int level) {
    std::sort(file.ranges.begin(), file.ranges.end(),
              [](const StreamedSogRange& a, const StreamedSogRange& b) { return a.offset < b.offset; });
    for (std::size_t i = 1; i < file.ranges.size(); ++i) {
        const StreamedSogRange& before = file.ranges[i - 1];
        if (before.offset + before.count > file.ranges[i].offset)
            meta_error(path, "level " + std::to_string(level) + ": " + file.ranges[i].where + " overlaps " +
                                 before.where + " in " + file.file.filename().string() + " (records " +
                                 std::to_string(file.ranges[i].offset) + " and " + std::to_string(before.offset) +
                                 " + " + std::to_string(before.count) + ")");
    }
}

StreamedSogLevel read_level(int level, const std::vector<Leaf>& leaves, const std::vector<std::string>& filenames,
                            const fs::path& path) {
    const std::string key = std::to_string(level);
    StreamedSogLevel out;
    out.level = level;
    std::map<std::uint64_t, std::size_t> slot_of_file;
    for (const Leaf& leaf : leaves) {
        const std::string where = leaf.where + ".lods[\"" + key + "\"]";
        if (!leaf.lods->contains(key)) {
            if (out.missing_in.empty()) out.missing_in = leaf.where;
            continue;
        }
        const json& entry = (*leaf.lods)[key];
        if (!entry.is_object()) meta_error(path, where + " must be an object");
        const std::uint64_t index = nonnegative(entry, "file", where, path);
        if (index >= filenames.size())
            meta_error(path, where + ": file index " + std::to_string(index) + ", but \"filenames\" has only " +
                                 std::to_string(filenames.size()) + " entries");
        const StreamedSogRange range{nonnegative(entry, "offset", where, path),
                                     nonnegative(entry, "count", where, path), leaf.where};
        if (range.offset > (std::uint64_t{1} << 40) || range.count > (std::uint64_t{1} << 40))
            meta_error(path, where + ": offset or count beyond any real file");
        auto [slot, added] = slot_of_file.try_emplace(index, out.files.size());
        if (added) out.files.push_back({path.parent_path() / filenames[index], {}, 0});
        StreamedSogFile& file = out.files[slot->second];
        file.ranges.push_back(range);
        file.gaussians += range.count;
        out.gaussians += range.count;
    }
    for (StreamedSogFile& file : out.files) check_ranges(file, path, level);
    return out;
}

}  // namespace

bool is_streamed_sog(const fs::path& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) return fs::exists(path / kMetaName, ec);
    return path.filename() == kMetaName;
}

StreamedSog read_streamed_sog_meta(const fs::path& given) {
    const fs::path path = meta_file_of(given);
    const json doc = parse_document(path);
    const std::vector<std::string> filenames = read_filenames(doc, path);
    if (!doc.contains("tree")) meta_error(path, "missing \"tree\"");
    std::vector<Leaf> leaves;
    collect_leaves(doc["tree"], "tree", 0, path, leaves);
    if (leaves.empty()) meta_error(path, "no node of \"tree\" has \"lods\"");
    // Level keys are checked even where "lodLevels" says how many there are: a key beyond it is a
    // level the file would silently drop.
    const int levels = level_count(doc, leaves, path);
    for (const Leaf& leaf : leaves)
        for (const auto& item : leaf.lods->items())
            if (parse_level_key(item.key(), leaf.where, path) >= levels)
                meta_error(path, leaf.where + ".lods: level " + item.key() + " is beyond \"lodLevels\" (" +
                                     std::to_string(levels) + ")");
    StreamedSog sog;
    sog.meta = path;
    for (int level = 0; level < levels; ++level) {
        sog.levels.push_back(read_level(level, leaves, filenames, path));
        for (const StreamedSogFile& file : sog.levels.back().files) {
            std::error_code ec;
            if (!fs::exists(file.file, ec))
                meta_error(path, "level " + std::to_string(level) + ": its chunk file " + file.file.string() +
                                     " does not exist");
        }
    }
    return sog;
}

const StreamedSogLevel& streamed_sog_level(const StreamedSog& sog, int level) {
    if (level < 0 || static_cast<std::size_t>(level) >= sog.levels.size())
        meta_error(sog.meta, "has no level " + std::to_string(level) + " (levels 0.." +
                                 std::to_string(sog.levels.size() - 1) + ", 0 the finest)");
    const StreamedSogLevel& out = sog.levels[static_cast<std::size_t>(level)];
    if (!out.missing_in.empty())
        meta_error(sog.meta, "level " + std::to_string(level) + " is missing from " + out.missing_in +
                                 ", so the scene at that level has a hole");
    return out;
}

namespace {

// The chunk file's Gaussians in record order, before any is dropped: the ranges count records. Chunk
// files are SOG (splat-transform writes nothing else); other splat files are read whole and must
// drop nothing, or the ranges would no longer line up.
SplatCloud decode_chunk_file(const fs::path& file, LoadReport& local) {
    if (detect_splat_format(file) == SplatFileFormat::sog) return decode_sog(file, local);
    SplatCloud cloud = load_splat_file(file, &local);
    if (local.dropped() > 0)
        fail_file(file.string(), "dropped " + std::to_string(local.dropped()) +
                                     " bad Gaussians, so the tree's record ranges no longer line up");
    return cloud;
}

}  // namespace

SplatCloud read_streamed_sog_file(const StreamedSogFile& part, LoadReport* report) {
    LoadReport local;
    SplatCloud cloud = decode_chunk_file(part.file, local);
    std::vector<std::uint8_t> keep(cloud.size(), 0);
    for (const StreamedSogRange& range : part.ranges) {
        if (range.offset + range.count > cloud.size())
            fail_file(part.file.string(), "holds " + std::to_string(cloud.size()) + " Gaussians, but " + range.where +
                                              " asks for records " + std::to_string(range.offset) + " to " +
                                              std::to_string(range.offset + range.count) +
                                              " (a truncated or replaced chunk)");
        std::fill_n(keep.begin() + static_cast<std::ptrdiff_t>(range.offset), range.count, std::uint8_t{1});
    }
    cloud.keep_only(keep);  // ranges are sorted, so the order is the ranges' order
    local.gaussians_in_file = cloud.size();
    finish_load(cloud, local, report, part.file.string());
    return cloud;
}

}  // namespace splat_lod::io
