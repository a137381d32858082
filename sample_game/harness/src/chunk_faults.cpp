#include "sample_game/harness/chunk_faults.h"

#include <algorithm>
#include <fstream>
#include <iterator>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "splat_lod/core/chunk_reader.h"

namespace sample_game {
namespace fs = std::filesystem;

namespace {

constexpr const char* kSetAside = ".soak-original";

bool inside(const fs::path& path, const fs::path& folder) {
    const fs::path p = fs::weakly_canonical(path), f = fs::weakly_canonical(folder);
    auto [end, unused] = std::mismatch(f.begin(), f.end(), p.begin(), p.end());
    return end == f.end();
}

std::vector<std::uint8_t> read_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) engine::fail(path.string() + ": cannot open");
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

std::string_view to_string(FaultKind kind) {
    switch (kind) {
        case FaultKind::removed:
            return "removed";
        case FaultKind::truncated:
            return "truncated";
        case FaultKind::replaced:
            return "replaced";
        case FaultKind::corrupted:
            return "corrupted";
    }
    return "?";
}

void make_linked_world_copy(const fs::path& world, const fs::path& copy) {
    if (inside(copy, world))
        engine::fail(copy.string() + ": the soak's copy of the world must lie outside the world " + world.string());
    std::error_code ec;
    fs::remove_all(copy, ec);  // a copy of hard links: removing it never touches the originals
    if (ec) engine::fail(copy.string() + ": cannot remove the previous copy: " + ec.message());
    fs::create_directories(copy);
    for (auto it = fs::recursive_directory_iterator(world); it != fs::recursive_directory_iterator(); ++it) {
        const fs::path relative = fs::relative(it->path(), world);
        const fs::path target = copy / relative;
        if (it->is_directory()) {
            fs::create_directories(target);
        } else if (it->is_regular_file()) {
            if (relative == splat_lod::world::kManifestFileName) {
                fs::copy_file(it->path(), target);
                continue;
            }
            fs::create_hard_link(it->path(), target, ec);
            if (ec) fs::copy_file(it->path(), target);
        }
    }
}

ChunkFaults::ChunkFaults(fs::path folder, const splat_lod::world::WorldManifest& manifest)
    : folder_(std::move(folder)), manifest_(manifest) {}

ChunkFaults::~ChunkFaults() {
    try {
        restore_all();
    } catch (const std::exception&) {
        // The copy is rebuilt by the next soak run; nothing of the user's is damaged.
    }
}

fs::path ChunkFaults::file(std::size_t chunk) const {
    return folder_ / manifest_.chunks.at(chunk).file;
}

void ChunkFaults::apply(std::size_t chunk, FaultKind kind, std::size_t donor) {
    if (find(manifest_.chunks.at(chunk).id) != nullptr) return;
    const fs::path path = file(chunk), original = fs::path(path.string() + kSetAside);
    // The damaged bytes are made before the original is set aside (the donor may be read first).
    std::vector<std::uint8_t> bytes;
    if (kind == FaultKind::truncated) {
        bytes = read_bytes(path);
        bytes.resize(bytes.size() * 6 / 10);
    } else if (kind == FaultKind::corrupted) {
        bytes = read_bytes(path);
        const splat_lod::world::ChunkEntry& entry = manifest_.chunks[chunk];
        for (const auto& block : splat_lod::world::record_block_bytes(path, entry)) {
            const std::uint64_t at = block.offset;
            if (at >= bytes.size())
                engine::fail(path.string() + ": shorter than its manifest entry says; cannot corrupt it in place");
            bytes[static_cast<std::size_t>(at)] ^= 1u;
        }
    } else if (kind == FaultKind::replaced) {
        // The donor's own bytes, also when the donor itself is damaged (its original is set aside).
        const bool donor_damaged = find(manifest_.chunks.at(donor).id) != nullptr;
        bytes = read_bytes(donor_damaged ? fs::path(file(donor).string() + kSetAside) : file(donor));
    }
    fs::rename(path, original);
    if (kind != FaultKind::removed) engine::write_file_atomic(path, bytes);
    active_.push_back({chunk, manifest_.chunks[chunk].id, kind});
}

void ChunkFaults::restore_all() {
    while (!active_.empty()) {
        const fs::path path = file(active_.back().chunk);
        fs::rename(fs::path(path.string() + kSetAside), path);
        active_.pop_back();
    }
}

const ChunkFault* ChunkFaults::find(std::string_view chunk_id) const {
    const auto it =
        std::find_if(active_.begin(), active_.end(), [&](const ChunkFault& f) { return f.chunk_id == chunk_id; });
    return it == active_.end() ? nullptr : &*it;
}

}  // namespace sample_game
