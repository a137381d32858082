// Generation and staging folders and the clean-up after a commit (world/world_folder.h).
//
// Output safety. world.json is the world's single commit point. A run writes every file it makes
// into a new generation folder, gen-<n>/ with n one above every gen-<n> already there, so no file
// that the current manifest names is ever replaced or removed; each file is synced to disk before
// it is renamed into place (engine::write_file_atomic). The manifest naming the new files is
// written last, atomically; only then does the run remove what the new manifest does not name: the
// previous generation, leftovers of killed runs and the flat chunks/ and meshes/ files of worlds
// made before generation folders. Killed at any moment, a run leaves either the previous world.json
// with every file it names untouched, or the new one complete (plus files the next run removes).
// Chunk files keep their bytes: only the folder they are in changes with the generation. A sharded
// bake stages its files in staging-<hash>/gen/, which the merge renames to the new gen-<n>.
#include "world_folder.h"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <set>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include "engine/core/error.h"

namespace splat_lod::world {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kGenerationPrefix = "gen-";

// The names in `folder`, listed before anything is removed from it (none when it cannot be read).
std::vector<std::string> entry_names(const fs::path& folder) {
    std::vector<std::string> names;
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
        names.push_back(it->path().filename().string());
    return names;
}

// A file of the flat layout of worlds made before generation folders: chunks/chunk_*.lod.ply,
// meshes/{house,fence,post,terrain}.glb, or a temporary of one.
bool flat_layout_file(const std::string& folder, const std::string& name) {
    if (folder == "chunks") return name.rfind("chunk_", 0) == 0 && name.find(".lod.ply") != std::string::npos;
    for (const char* mesh : {"house.glb", "fence.glb", "post.glb", "terrain.glb"})
        if (name == mesh || name.rfind(std::string(mesh) + ".tmp-", 0) == 0) return true;
    return false;
}

std::uint32_t float_bits(float v) {
    return std::bit_cast<std::uint32_t>(v);
}

}  // namespace

void create_world_folder(const std::filesystem::path& output) {
    std::error_code ec;
    std::filesystem::create_directories(output, ec);
    if (ec) engine::fail(output.string() + ": cannot create the world's folder: " + ec.message());
}

std::uint64_t generation_number(const std::string& name) {
    if (name.size() <= kGenerationPrefix.size() || name.compare(0, kGenerationPrefix.size(), kGenerationPrefix) != 0)
        return 0;
    std::uint64_t n = 0;
    const char* const last = name.data() + name.size();
    const auto [end, error] = std::from_chars(name.data() + kGenerationPrefix.size(), last, n);
    if (error != std::errc() || end != last) return 0;
    return name.substr(kGenerationPrefix.size()) == std::to_string(n) ? n : 0;  // "gen-01" is not one of ours
}

fs::path new_generation(const fs::path& output) {
    std::uint64_t highest = 0;
    std::error_code ec;
    for (fs::directory_iterator it(output, ec), end; !ec && it != end; it.increment(ec))
        highest = std::max(highest, generation_number(it->path().filename().string()));
    if (ec) engine::fail(output.string() + ": cannot list the world's folder: " + ec.message());
    return std::string(kGenerationPrefix) + std::to_string(highest + 1);
}

std::string staging_folder_name(std::uint64_t seed, float size_m, float chunk_size_m, float density,
                                const std::string& generator) {
    char numbers[96];
    std::snprintf(numbers, sizeof numbers, "seed %llu; size %08x; chunk %08x; density %08x; ",
                  static_cast<unsigned long long>(seed), float_bits(size_m), float_bits(chunk_size_m),
                  float_bits(density));
    std::uint64_t hash = 14695981039346656037ull;  // FNV-1a, 64 bits
    for (const char c : std::string(numbers) + generator) {
        hash ^= static_cast<unsigned char>(c);
        hash *= 1099511628211ull;
    }
    char name[32];
    std::snprintf(name, sizeof name, "staging-%016llx", static_cast<unsigned long long>(hash));
    return name;
}

void remove_unnamed_files(const fs::path& folder, const WorldManifest& m) {
    std::set<fs::path> named;
    for (const auto& c : m.chunks) named.insert(c.file.lexically_normal());
    for (const auto& g : m.groups) named.insert(g.file.lexically_normal());
    for (const auto& p : m.props) named.insert(p.mesh.lexically_normal());
    if (!m.terrain_mesh.empty()) named.insert(m.terrain_mesh.lexically_normal());
    std::set<std::string> named_tops;
    for (const auto& path : named) named_tops.insert(path.begin()->string());

    // A world of the flat layout keeps its folders as they are (with meshes it did not place).
    const bool flat_world = named_tops.count("chunks") > 0 || named_tops.count("meshes") > 0;
    const std::string manifest_temporary = std::string(kManifestFileName) + ".tmp-";
    const std::string staging = staging_folder_name(m.seed, m.size_m, m.chunk_size_m, m.density, m.generator);
    std::error_code ignored;
    for (const std::string& name : entry_names(folder)) {
        const fs::path path = folder / name;
        if (generation_number(name) > 0 && !named_tops.count(name)) {
            fs::remove_all(path, ignored);
        } else if (generation_number(name) > 0 && fs::is_directory(path / "groups", ignored)) {
            // A generation whose chunks are still named may hold groups that newer ones replaced.
            for (const std::string& file : entry_names(path / "groups"))
                if (!named.count(fs::path(name) / "groups" / file)) fs::remove(path / "groups" / file, ignored);
            fs::remove(path / "groups", ignored);  // only when empty
        } else if (!flat_world && (name == "chunks" || name == "meshes") && fs::is_directory(path, ignored)) {
            for (const std::string& file : entry_names(path)) {
                if (flat_layout_file(name, file) && !named.count(fs::path(name) / file))
                    fs::remove(path / file, ignored);
            }
            fs::remove(path, ignored);  // only when empty
        } else if (name.rfind(manifest_temporary, 0) == 0) {
            fs::remove(path, ignored);
        } else if (name == staging && !named_tops.count(name)) {
            const FolderFlock no_shard_running(path, true);
            if (no_shard_running.held()) fs::remove_all(path, ignored);
        }
    }
}

void remove_generation_unless_committed(const fs::path& output, const fs::path& generation) {
    std::error_code ec;
    try {
        if (fs::exists(output / kManifestFileName, ec)) {
            const WorldManifest current = read_world_manifest(output / kManifestFileName);
            for (const auto* list : {&current.chunks, &current.groups})
                for (const auto& entry : *list)
                    if (*entry.file.begin() == generation) return;
        }
    } catch (const engine::Error&) {
        return;  // unreadable: keep the files, the next run removes them if they are not named
    }
    fs::remove_all(output / generation, ec);
}

FolderFlock::FolderFlock(const fs::path& folder, bool exclusive)
    : fd_(::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {
    if (fd_ < 0) {
        problem_ = folder.string() + ": cannot open the folder: " + std::strerror(errno);
        return;
    }
    if (::flock(fd_, (exclusive ? LOCK_EX : LOCK_SH) | LOCK_NB) == 0) return;
    const int error = errno;
    busy_ = error == EWOULDBLOCK;
    problem_ = folder.string() + ": cannot lock the folder: " + std::strerror(error);
    ::close(std::exchange(fd_, -1));
}

FolderFlock::~FolderFlock() {
    if (fd_ >= 0) ::close(fd_);
}

}  // namespace splat_lod::world
