// The soak's fault injector (sample_game/harness/chunk_faults.h) never touches the user's files: the copy
// links them, damage replaces the copy's directory entries, restore brings the exact bytes back.
#include <sys/stat.h>

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "sample_game/harness/chunk_faults.h"
#include "test_support.h"

namespace fs = std::filesystem;
namespace sw = splat_lod::world;
using namespace sample_game;

namespace {

std::vector<std::uint8_t> bytes_of(std::size_t n, std::uint8_t seed) {
    std::vector<std::uint8_t> b(n);
    for (std::size_t i = 0; i < n; ++i) b[i] = static_cast<std::uint8_t>(seed + i * 7);
    return b;
}

ino_t inode(const fs::path& p) {
    struct stat s {};
    return ::stat(p.c_str(), &s) == 0 ? s.st_ino : 0;
}

struct FakeWorld {
    fs::path folder, copy;
    sw::WorldManifest manifest;
    std::vector<std::vector<std::uint8_t>> files;
};

FakeWorld make_fake_world(const std::string& name) {
    FakeWorld w;
    const fs::path root = engine::test::output_dir("sample_game") / name;
    fs::remove_all(root);
    w.folder = root / "world";
    w.copy = root / "copy";
    fs::create_directories(w.folder / "chunks");
    fs::create_directories(w.folder / "meshes");
    engine::write_text_file_atomic(w.folder / "world.json", "{}");
    engine::write_text_file_atomic(w.folder / "meshes" / "prop.gltf", "{\"asset\":{}}");
    for (int i = 0; i < 3; ++i) {
        sw::ChunkEntry e;
        e.id = "chunk_" + std::to_string(i);
        e.file = fs::path("chunks") / (e.id + ".lod.ply");
        // 100 header bytes and records of 10 bytes, as the file's size says: 90 + 10 i records.
        e.header_bytes = 100;
        e.vertex_bytes = 10;
        e.prefix_count = {90u + 10u * static_cast<unsigned>(i), 4, 4, 1};
        e.file_bytes = e.prefix_bytes(1);
        w.files.push_back(bytes_of(1000 + 100 * static_cast<std::size_t>(i), static_cast<std::uint8_t>(i)));
        engine::write_file_atomic(w.folder / e.file, w.files.back());
        w.manifest.chunks.push_back(e);
    }
    return w;
}

}  // namespace

TEST(ChunkFaultsTest, TheCopyLinksEveryFileButTheManifest) {
    const FakeWorld w = make_fake_world("faults_copy");
    make_linked_world_copy(w.folder, w.copy);
    EXPECT_EQ(inode(w.copy / "chunks" / "chunk_1.lod.ply"), inode(w.folder / "chunks" / "chunk_1.lod.ply"));
    EXPECT_EQ(inode(w.copy / "meshes" / "prop.gltf"), inode(w.folder / "meshes" / "prop.gltf"));
    EXPECT_NE(inode(w.copy / "world.json"), inode(w.folder / "world.json"));
    EXPECT_EQ(engine::read_text_file(w.copy / "world.json"), "{}");
    // A copy inside the world would be damaged along with the world: refused.
    EXPECT_THROW(make_linked_world_copy(w.folder, w.folder / "copy"), engine::Error);
    EXPECT_THROW(make_linked_world_copy(w.folder, w.folder), engine::Error);
}

TEST(ChunkFaultsTest, DamageGoesToTheCopyOnlyAndRestoreBringsTheBytesBack) {
    const FakeWorld w = make_fake_world("faults_damage");
    make_linked_world_copy(w.folder, w.copy);
    {
        ChunkFaults faults(w.copy, w.manifest);
        faults.apply(0, FaultKind::removed);
        faults.apply(1, FaultKind::truncated);
        faults.apply(2, FaultKind::replaced, 0);
        ASSERT_EQ(faults.active().size(), 3u);
        ASSERT_NE(faults.find("chunk_1"), nullptr);
        EXPECT_EQ(faults.find("chunk_1")->kind, FaultKind::truncated);
        EXPECT_FALSE(fs::exists(w.copy / "chunks" / "chunk_0.lod.ply"));
        EXPECT_EQ(fs::file_size(w.copy / "chunks" / "chunk_1.lod.ply"), 1100u * 6 / 10);
        EXPECT_EQ(engine::read_binary_file(w.copy / "chunks" / "chunk_2.lod.ply"), w.files[0]);
        // The world's own files are unchanged.
        for (std::size_t i = 0; i < 3; ++i)
            EXPECT_EQ(engine::read_binary_file(w.folder / w.manifest.chunks[i].file), w.files[i]) << i;
        faults.restore_all();
        EXPECT_TRUE(faults.active().empty());
        for (std::size_t i = 0; i < 3; ++i)
            EXPECT_EQ(engine::read_binary_file(w.copy / w.manifest.chunks[i].file), w.files[i]) << i;
        faults.apply(1, FaultKind::removed);
    }  // the destructor restores what is still damaged
    {
        // corrupted: the same size, one bit flipped at the first record of every checksum block
        // (chunk 1: stream level 4 holds record 0, level 3 records 1..3, level 2 none, level 1 4..99).
        ChunkFaults faults(w.copy, w.manifest);
        faults.apply(1, FaultKind::corrupted);
        const std::vector<std::uint8_t> bytes = engine::read_binary_file(w.copy / "chunks" / "chunk_1.lod.ply");
        ASSERT_EQ(bytes.size(), w.files[1].size());
        std::vector<std::size_t> changed;
        for (std::size_t k = 0; k < bytes.size(); ++k)
            if (bytes[k] != w.files[1][k]) changed.push_back(k);
        EXPECT_EQ(changed, (std::vector<std::size_t>{100, 110, 140}));
        EXPECT_EQ(bytes[110] ^ w.files[1][110], 1);
        EXPECT_EQ(engine::read_binary_file(w.folder / "chunks" / "chunk_1.lod.ply"), w.files[1]);
    }
    EXPECT_EQ(engine::read_binary_file(w.copy / "chunks" / "chunk_1.lod.ply"), w.files[1]);
    EXPECT_EQ(engine::read_binary_file(w.copy / "chunks" / "chunk_1.lod.ply"), w.files[1]);
}
