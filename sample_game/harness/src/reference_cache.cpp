#include "sample_game/harness/reference_cache.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <set>

#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "formatted.h"
#include "splat_lod/core/world_manifest.h"

namespace sample_game {
namespace fs = std::filesystem;

namespace {

constexpr const char* kKeyFileName = "reference.json";
constexpr const char* kTemporaryPrefix = ".tmp-";
constexpr const char* kOldPrefix = ".old-";

[[noreturn]] void broken(const fs::path& file, const std::string& problem) {
    engine::fail("sample_game_harness: reference " + file.string() + ": " + problem +
                 "; make the reference again with `sample_game_harness --reference --force` (same options)");
}

// Temporaries (".tmp-<key>-<pid>", ".old-<key>-<pid>") of writers that no longer run.
void remove_stale_folders(const fs::path& parent) {
    std::error_code ec;
    for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.rfind(kTemporaryPrefix, 0) != 0 && name.rfind(kOldPrefix, 0) != 0) continue;
        const std::size_t dash = name.rfind('-');
        long pid = 0;
        const auto [end_ptr, error] = std::from_chars(name.data() + dash + 1, name.data() + name.size(), pid);
        if (error != std::errc() || end_ptr != name.data() + name.size() || pid <= 0) continue;
        if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
            std::error_code ignored;
            fs::remove_all(it->path(), ignored);
        }
    }
}

}  // namespace

std::vector<std::size_t> reference_frame_indices(const std::vector<PathPose>& poses) {
    std::set<std::size_t> chosen;
    for (std::size_t k = 0; k < kSegmentCount; ++k) {
        std::size_t first = poses.size(), count = 0;
        for (std::size_t i = 0; i < poses.size(); ++i)
            if (static_cast<std::size_t>(poses[i].segment) == k) {
                first = std::min(first, i);
                ++count;
            }
        const auto wanted = static_cast<std::size_t>(kReferenceFramesPerSegment[k]);
        for (std::size_t i = 0; i < wanted && count > 0; ++i) {
            const std::size_t frame = first + std::min(count - 1, (2 * i + 1) * count / (2 * wanted));
            chosen.insert(frame);
            if (frame + 1 < poses.size()) chosen.insert(frame + 1);  // its successor: a consecutive pair
        }
    }
    return {chosen.begin(), chosen.end()};
}

std::string ReferenceKey::json() const {
    nlohmann::ordered_json j;
    j["format_version"] = version;
    j["world_chunks_crc32"] = formatted("%08x", world_checksum);
    j["path_crc32"] = formatted("%08x", path_checksum);
    j["width"] = width;
    j["height"] = height;
    j["path_frames"] = frames;
    j["fov_y_deg"] = fov_y_deg;
    j["supersample"] = supersample;
    j["mode"] = "baseline, every chunk resident";
    j["frames"] = frame_indices;
    return j.dump(2) + "\n";
}

std::string ReferenceKey::folder_name() const {
    const std::string text = json();
    const auto crc =
        splat_lod::world::checksum(std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
    return formatted("%dx%d_f%d_s%d_%08x", width, height, frames, supersample, crc);
}

ReferenceKey reference_key(const fs::path& world, int width, int height, const std::vector<PathPose>& poses,
                           double fov_y_deg, int supersample) {
    // The chunks and meshes, not the chunk groups: the reference draws every chunk and no group.
    ReferenceKey key;
    key.world_checksum = splat_lod::world::chunks_checksum(
        splat_lod::world::read_world_manifest(world / splat_lod::world::kManifestFileName));
    key.width = width;
    key.height = height;
    key.frames = static_cast<int>(poses.size());
    std::vector<float> values;
    for (const PathPose& p : poses)
        values.insert(values.end(), {p.eye.x, p.eye.y, p.eye.z, p.forward.x, p.forward.y, p.forward.z,
                                     static_cast<float>(p.segment)});
    key.path_checksum = splat_lod::world::checksum(
        std::span(reinterpret_cast<const std::uint8_t*>(values.data()), values.size() * sizeof(float)));
    key.fov_y_deg = fov_y_deg;
    key.supersample = supersample;
    key.frame_indices = reference_frame_indices(poses);
    return key;
}

fs::path reference_folder(const fs::path& world, const ReferenceKey& key) {
    return world / kReferenceFolderName / key.folder_name();
}

fs::path reference_frame_file(const fs::path& folder, std::size_t frame) {
    return folder / formatted("frame_%04zu.png", frame);
}

std::optional<CachedReference> read_reference(const fs::path& world, const ReferenceKey& key) {
    CachedReference cached;
    cached.folder = reference_folder(world, key);
    std::error_code ec;
    if (!fs::is_directory(cached.folder, ec)) return std::nullopt;
    const fs::path key_file = cached.folder / kKeyFileName;
    if (!fs::exists(key_file, ec)) broken(key_file, "missing");
    if (engine::read_text_file(key_file) != key.json()) broken(key_file, "names other inputs than this run's");
    for (const std::size_t frame : key.frame_indices) {
        const fs::path file = reference_frame_file(cached.folder, frame);
        if (!fs::exists(file, ec)) broken(file, "missing");
        engine::Image image;
        try {
            image = engine::read_png(file);
        } catch (const engine::Error& e) {
            broken(file, e.what());
        }
        if (image.width != key.width || image.height != key.height)
            broken(file, formatted("is %dx%d, the key says %dx%d", image.width, image.height, key.width, key.height));
        cached.frames[static_cast<int>(frame)] = splat_lod::eval::to_float(image);
    }
    return cached;
}

void write_reference(const fs::path& world, const ReferenceKey& key, const std::map<int, engine::Image>& frames) {
    const fs::path parent = world / kReferenceFolderName;
    const std::string name = key.folder_name();
    const std::string pid = std::to_string(static_cast<long>(::getpid()));
    fs::create_directories(parent);
    remove_stale_folders(parent);
    const fs::path temporary = parent / (kTemporaryPrefix + name + "-" + pid);
    std::error_code ec;
    fs::remove_all(temporary, ec);
    try {
        fs::create_directories(temporary);
        for (const std::size_t frame : key.frame_indices) {
            const auto it = frames.find(static_cast<int>(frame));
            if (it == frames.end() || it->second.width != key.width || it->second.height != key.height)
                engine::fail(formatted("sample_game_harness: reference: frame %zu was not rendered at %dx%d", frame,
                                       key.width, key.height));
            engine::write_png(reference_frame_file(temporary, frame), it->second);
        }
        engine::write_text_file_atomic(temporary / kKeyFileName, key.json());  // last: the folder is complete
        engine::sync_folder(temporary);
        const fs::path folder = parent / name, old = parent / (kOldPrefix + name + "-" + pid);
        if (fs::exists(folder, ec)) fs::rename(folder, old);
        fs::rename(temporary, folder);
        engine::sync_folder(parent);
        fs::remove_all(old, ec);
    } catch (const fs::filesystem_error& e) {
        fs::remove_all(temporary, ec);
        engine::fail("sample_game_harness: reference " + (parent / name).string() + ": " + e.what());
    } catch (...) {
        fs::remove_all(temporary, ec);
        throw;
    }
}

}  // namespace sample_game
