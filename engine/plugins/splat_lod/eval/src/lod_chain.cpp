#include "splat_lod/eval/lod_chain.h"

#include <algorithm>
#include <optional>

#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "splat_lod/eval/eval_scene.h"

namespace splat_lod::eval {
namespace {

using nlohmann::json;

// Bounds that no real chain reaches; they keep hostile files from recursing or allocating without end.
constexpr int kMaxTreeDepth = 64;
constexpr int kMaxLevels = 64;

[[noreturn]] void chain_error(const std::filesystem::path& path, const std::string& problem) {
    engine::fail(path.string() + ": " + problem);
}

json parse_document(const std::filesystem::path& path) {
    const std::string text = engine::read_text_file(path);
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::parse_error& e) {
        chain_error(path, std::string("not valid JSON: ") + e.what());
    }
    if (!doc.is_object()) chain_error(path, "expected a JSON object (a lod-meta.json)");
    return doc;
}

std::vector<std::string> read_filenames(const json& doc, const std::filesystem::path& path) {
    if (!doc.contains("filenames")) chain_error(path, "missing \"filenames\"");
    const json& names = doc["filenames"];
    if (!names.is_array() || names.empty()) chain_error(path, "\"filenames\" must be a non-empty array of file names");
    std::vector<std::string> out;
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (!names[i].is_string() || names[i].get<std::string>().empty())
            chain_error(path, "\"filenames\"[" + std::to_string(i) + "] must be a non-empty string");
        out.push_back(names[i].get<std::string>());
    }
    return out;
}

// A node of the tree with "lods", and where it is ("tree.children[1]") for messages.
struct Leaf {
    const json* lods;
    std::string where;
};

void collect_leaves(const json& node, const std::string& where, int depth, const std::filesystem::path& path,
                    std::vector<Leaf>& leaves) {
    if (!node.is_object()) chain_error(path, where + " must be an object");
    if (depth > kMaxTreeDepth)
        chain_error(path, where + ": the tree is nested deeper than " + std::to_string(kMaxTreeDepth));
    if (node.contains("lods")) {
        if (!node["lods"].is_object()) chain_error(path, where + ".lods must be an object");
        leaves.push_back({&node["lods"], where});
    }
    if (node.contains("children")) {
        const json& children = node["children"];
        if (!children.is_array()) chain_error(path, where + ".children must be an array");
        for (std::size_t i = 0; i < children.size(); ++i)
            collect_leaves(children[i], where + ".children[" + std::to_string(i) + "]", depth + 1, path, leaves);
    }
}

int parse_level_key(const std::string& key, const std::string& where, const std::filesystem::path& path) {
    const bool digits = !key.empty() && key.size() <= 2 && key.find_first_not_of("0123456789") == std::string::npos;
    const int level = digits ? std::stoi(key) : -1;
    if (level < 0 || level >= kMaxLevels) chain_error(path, where + ".lods: \"" + key + "\" is not a level number");
    return level;
}

// "lodLevels" when given, else one more than the highest level any leaf lists.
int level_count(const json& doc, const std::vector<Leaf>& leaves, const std::filesystem::path& path) {
    if (doc.contains("lodLevels")) {
        const json& n = doc["lodLevels"];
        if (!n.is_number_integer() || n.get<long long>() < 1 || n.get<long long>() > kMaxLevels)
            chain_error(path, "\"lodLevels\" must be an integer from 1 to " + std::to_string(kMaxLevels));
        return n.get<int>();
    }
    int count = 0;
    for (const Leaf& leaf : leaves)
        for (const auto& item : leaf.lods->items())
            count = std::max(count, parse_level_key(item.key(), leaf.where, path) + 1);
    if (count == 0) chain_error(path, "the tree lists no level");
    return count;
}

std::uint64_t nonnegative(const json& entry, const char* key, const std::string& where,
                          const std::filesystem::path& path) {
    if (!entry.contains(key)) chain_error(path, where + ": missing \"" + key + "\"");
    const json& v = entry[key];
    if (!v.is_number_integer() || v.get<long long>() < 0)
        chain_error(path, where + ": \"" + key + "\" must be a non-negative integer");
    return v.get<std::uint64_t>();
}

// The file of `level`: the same index in every leaf, or an error saying why the level is not one file.
LodChainLevel read_level(int level, const std::vector<Leaf>& leaves, const std::vector<std::string>& filenames,
                         const std::filesystem::path& path) {
    const std::string key = std::to_string(level);
    std::optional<std::uint64_t> file;
    LodChainLevel out;
    out.level = level;
    for (const Leaf& leaf : leaves) {
        const std::string where = leaf.where + ".lods[\"" + key + "\"]";
        if (!leaf.lods->contains(key))
            chain_error(path, "level " + key + " is missing from " + leaf.where +
                                  ", so no file holds the whole scene at that level");
        const json& entry = (*leaf.lods)[key];
        if (!entry.is_object()) chain_error(path, where + " must be an object");
        const std::uint64_t index = nonnegative(entry, "file", where, path);
        if (index >= filenames.size())
            chain_error(path, where + ": file index " + std::to_string(index) + ", but \"filenames\" has only " +
                                  std::to_string(filenames.size()) + " entries");
        if (file && *file != index)
            chain_error(path, "level " + key + " is split over files \"" + filenames[*file] + "\" and \"" +
                                  filenames[index] + "\" (" + where +
                                  "); the comparison needs one file per level holding the whole scene");
        file = index;
        if (entry.contains("count")) out.gaussians += nonnegative(entry, "count", where, path);
    }
    out.file = path.parent_path() / filenames[*file];
    std::error_code ec;
    if (!std::filesystem::exists(out.file, ec))
        chain_error(path, "level " + key + ": its file " + out.file.string() + " does not exist");
    return out;
}

}  // namespace

std::string chain_method_name(int level) {
    return "chain_L" + std::to_string(level);
}

LodChain read_lod_chain(const std::filesystem::path& path) {
    const json doc = parse_document(path);
    const std::vector<std::string> filenames = read_filenames(doc, path);
    if (!doc.contains("tree")) chain_error(path, "missing \"tree\"");
    std::vector<Leaf> leaves;
    collect_leaves(doc["tree"], "tree", 0, path, leaves);
    if (leaves.empty()) chain_error(path, "no node of \"tree\" has \"lods\"");
    // Level keys are checked even where "lodLevels" says how many there are: a key beyond it is a
    // level the file would silently drop.
    const int levels = level_count(doc, leaves, path);
    for (const Leaf& leaf : leaves)
        for (const auto& item : leaf.lods->items())
            if (parse_level_key(item.key(), leaf.where, path) >= levels)
                chain_error(path, leaf.where + ".lods: level " + item.key() + " is beyond \"lodLevels\" (" +
                                      std::to_string(levels) + ")");
    LodChain chain;
    chain.meta = path;
    for (int level = 0; level < levels; ++level) chain.levels.push_back(read_level(level, leaves, filenames, path));
    return chain;
}

std::vector<ComparisonScene> chain_comparisons(const LodChain& chain, const std::filesystem::path& main_file,
                                               std::shared_ptr<const SplatCloud> main_cloud) {
    std::vector<ComparisonScene> out;
    for (const LodChainLevel& level : chain.levels) {
        std::error_code ec;
        const bool is_main = main_cloud && std::filesystem::equivalent(level.file, main_file, ec);
        ComparisonScene comparison;
        comparison.method = chain_method_name(level.level);
        comparison.description = "level " + std::to_string(level.level) + " of " + chain.meta.filename().string() +
                                 " (" + level.file.lexically_relative(chain.meta.parent_path()).string() + ", " +
                                 std::to_string(level.gaussians) + " Gaussians) with the baseline renderer";
        comparison.load = [file = level.file, cloud = is_main ? main_cloud : nullptr]() {
            return cloud ? make_splat_scene(cloud, file) : load_splat_file_scene(file);
        };
        out.push_back(std::move(comparison));
    }
    return out;
}

}  // namespace splat_lod::eval
