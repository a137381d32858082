// Compressed chunk files (splat_lod/core/compact_chunk.h, chunk_writer.h, chunk_reader.h): what the
// reader gives back is exactly the compact records of each block decoded, ranges and stream levels read
// alone agree with the whole file, hard values survive, and every kind of damage is an error that names
// the file while the rest of the file still reads.
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>
#include <tuple>

#include <unistd.h>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "splat_io_test_helpers.h"
#include "splat_lod/core/chunk_reader.h"
#include "splat_lod/core/chunk_writer.h"
#include "splat_lod/core/compact_chunk.h"
#include "splat_lod/core/compact_gaussians.h"
#include "splat_lod/core/stream_levels.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;
namespace sw = splat_lod::world;
using splat_io_test::error_of;
using splat_lod::SplatCloud;

// A chunk-like cloud: `n` Gaussians over a 64 m square, every bake level, in stream order.
SplatCloud chunk_cloud(std::size_t n, int sh_degree, std::uint32_t seed, const sw::StreamLevelRule& rule) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    SplatCloud c;
    c.resize(n);
    c.set_sh_degree(sh_degree);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint8_t level = static_cast<std::uint8_t>(1 + i % 4);
        c.positions[i] = glm::vec3(32.0f * u(rng), 3.0f * u(rng), 32.0f * u(rng));
        c.rotations[i] = {u(rng), u(rng), u(rng), u(rng) + 1.5f};
        const float size = -4.0f + 1.2f * float(level) + 0.5f * u(rng);
        c.log_scales[i] = glm::vec3(size, size - 0.5f, size - 2.0f * std::abs(u(rng)));
        c.opacity_logits[i] = 3.0f * u(rng);
        c.sh_dc[i] = glm::vec3(u(rng), 1.5f * u(rng), 0.2f * u(rng));
        for (float& v : std::span(c.sh_rest).subspan(i * c.sh_rest_stride(), c.sh_rest_stride())) v = 0.3f * u(rng);
        c.lod_level[i] = level;
        c.coverage_min[i] = level == 1 ? -1.0f : std::exp2(float(level) + u(rng));
        c.coverage_max[i] = level == 4 ? -1.0f : std::exp2(float(level) + 2.0f + u(rng));
    }
    return c.permuted(sw::stream_order(c, rule));
}

// What the file must give back: each record block's Gaussians encoded against ranges fitted to the
// block and decoded (compact_gaussians.h), so every field's error is the compact format's.
SplatCloud expected_records(const SplatCloud& cloud, const sw::ChunkEntry& entry) {
    SplatCloud out;
    out.resize(cloud.size());
    out.set_sh_degree(cloud.sh_degree);
    std::vector<std::uint32_t> sh(splat_lod::compact_sh_words(cloud.sh_degree));
    for (const sw::RecordBlock& block : sw::record_blocks(entry, 0, entry.prefix_count[0])) {
        const auto page = splat_lod::fit_compact_page(cloud, block.begin, block.end - block.begin, cloud.sh_degree);
        for (std::size_t i = block.begin; i < block.end; ++i) {
            splat_lod::encode_compact_sh(cloud, i, page, cloud.sh_degree, sh);
            splat_lod::decode_compact_into(splat_lod::encode_compact(cloud, i, page), sh, page, cloud.sh_degree, out,
                                           i);
        }
    }
    return out;
}

void expect_same(const SplatCloud& a, const SplatCloud& b, std::size_t offset = 0) {
    ASSERT_EQ(a.sh_degree, b.sh_degree);
    for (std::size_t i = 0; i < a.size(); ++i) {
        const std::size_t j = i + offset;
        ASSERT_EQ(a.positions[i], b.positions[j]) << i;
        ASSERT_EQ(a.log_scales[i], b.log_scales[j]) << i;
        ASSERT_EQ(a.opacity_logits[i], b.opacity_logits[j]) << i;
        ASSERT_EQ(a.sh_dc[i], b.sh_dc[j]) << i;
        ASSERT_EQ(a.rotations[i].w, b.rotations[j].w) << i;
        ASSERT_EQ(a.rotations[i].x, b.rotations[j].x) << i;
        ASSERT_EQ(a.lod_level[i], b.lod_level[j]) << i;
        ASSERT_EQ(a.coverage_min[i], b.coverage_min[j]) << i;
        ASSERT_EQ(a.coverage_max[i], b.coverage_max[j]) << i;
        for (std::size_t k = 0; k < a.sh_rest_stride(); ++k)
            ASSERT_EQ(a.sh_rest[i * a.sh_rest_stride() + k], b.sh_rest[j * b.sh_rest_stride() + k]) << i;
    }
}

class CompactChunkTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::path(::testing::TempDir()) / ("compact_chunk_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    sw::ChunkEntry write(const SplatCloud& cloud, const std::string& name = "c.splatc") {
        return sw::write_chunk_file(cloud, dir_, name, {1, -2}, rule_, sw::ChunkCodec::compact);
    }
    fs::path dir_;
    sw::StreamLevelRule rule_;
};

TEST_F(CompactChunkTest, GivesBackEachBlocksCompactRecordsAtEveryShDegree) {
    for (int degree = 0; degree <= 3; ++degree) {
        const SplatCloud cloud = chunk_cloud(9000, degree, 7 + degree, rule_);
        const sw::ChunkEntry e = write(cloud);
        EXPECT_EQ(e.codec, sw::ChunkCodec::compact);
        EXPECT_EQ(e.vertex_bytes, 0u);
        EXPECT_EQ(e.file_bytes, fs::file_size(dir_ / "c.splatc"));
        EXPECT_EQ(e.record_crc32.size(), sw::record_block_count(e));
        const SplatCloud back = sw::read_chunk_range(dir_ / "c.splatc", e, 0, e.prefix_count[0]);
        expect_same(back, expected_records(cloud, e));
        // Random values are the worst case for the codec: still well under the 77-byte PLY record.
        const double per_gaussian = double(e.file_bytes) / double(cloud.size());
        EXPECT_LT(per_gaussian, 4.0 * (5 + splat_lod::compact_sh_words(degree)) + 1.0) << "degree " << degree;
    }
}

TEST_F(CompactChunkTest, ManifestBoundsHoldForTheStoredGaussians) {
    const SplatCloud cloud = chunk_cloud(6000, 0, 3, rule_);
    const sw::ChunkEntry e = write(cloud);
    const SplatCloud back = sw::read_chunk_range(dir_ / "c.splatc", e, 0, e.prefix_count[0]);
    for (const SplatCloud* c : {&cloud, &back})
        for (std::size_t i = 0; i < c->size(); ++i)
            for (int a = 0; a < 3; ++a) {
                EXPECT_GE(c->positions[i][a], e.bounds_min[a]);
                EXPECT_LE(c->positions[i][a], e.bounds_max[a]);
            }
    // The prefix counts are those of the written cloud.
    const auto levels = sw::stream_levels(cloud, rule_);
    EXPECT_EQ(e.prefix_count[0], cloud.size());
    EXPECT_EQ(e.prefix_count[3], static_cast<std::uint64_t>(std::count(levels.begin(), levels.end(), 4)));
}

TEST_F(CompactChunkTest, RangesAndStreamLevelsReadAloneMatchTheWholeFile) {
    const SplatCloud cloud = chunk_cloud(20000, 1, 11, rule_);
    const sw::ChunkEntry e = write(cloud);
    const fs::path file = dir_ / "c.splatc";
    const SplatCloud whole = sw::read_chunk_range(file, e, 0, e.prefix_count[0]);
    for (int level = 1; level <= 4; ++level) {
        const auto [begin, end] = sw::level_range(e, level);
        const SplatCloud part = sw::read_chunk_range(file, e, begin, end);
        ASSERT_EQ(part.size(), end - begin);
        expect_same(part, whole, begin);
    }
    for (const auto& [begin, end] : std::vector<std::pair<std::uint64_t, std::uint64_t>>{
             {1, 2}, {4095, 4097}, {100, 9000}, {e.prefix_count[0] - 1, e.prefix_count[0]}, {5, 5}}) {
        const SplatCloud part = sw::read_chunk_range(file, e, begin, end);
        ASSERT_EQ(part.size(), end - begin);
        expect_same(part, whole, begin);
    }
}

TEST_F(CompactChunkTest, HardValuesStayFiniteAndInRange) {
    SplatCloud c = chunk_cloud(600, 3, 5, rule_);
    for (std::size_t i = 0; i < c.size(); ++i) {
        c.positions[i] = glm::vec3(1e4f, -3.0f, 0.25f);  // every block's box of zero width
        if (i % 5 == 0) c.log_scales[i] = glm::vec3(-20.0f);
        if (i % 5 == 1) c.log_scales[i] = glm::vec3(12.0f);
        if (i % 5 == 2) c.opacity_logits[i] = -40.0f;  // opacity 0
        if (i % 5 == 3) c.opacity_logits[i] = 40.0f;   // opacity 1
        if (i % 7 == 0) c.rotations[i] = {1.0f, 1e-9f, 0.0f, 0.0f};
    }
    c = c.permuted(sw::stream_order(c, rule_));
    const sw::ChunkEntry e = write(c);
    const SplatCloud back = sw::read_chunk_range(dir_ / "c.splatc", e, 0, e.prefix_count[0]);
    for (std::size_t i = 0; i < back.size(); ++i) {
        EXPECT_EQ(back.positions[i], c.positions[i]) << i;
        for (int a = 0; a < 3; ++a) EXPECT_TRUE(std::isfinite(back.log_scales[i][a])) << i;
        EXPECT_TRUE(std::isfinite(back.opacity_logits[i])) << i;
    }
    expect_same(back, expected_records(c, e));
}

TEST_F(CompactChunkTest, AnEmptyChunkIsAHeaderAlone) {
    const sw::ChunkEntry e = write(SplatCloud{});
    EXPECT_EQ(e.file_bytes, sw::kCompactChunkFixedHeaderBytes);
    EXPECT_EQ(sw::read_chunk_range(dir_ / "c.splatc", e, 0, 0).size(), 0u);
}

TEST_F(CompactChunkTest, UndrawableGaussiansAreRefusedAndNothingIsWritten) {
    SplatCloud c = chunk_cloud(100, 0, 2, rule_);
    c.sh_dc[40].y = std::numeric_limits<float>::quiet_NaN();
    const std::string message = error_of([&] { write(c); });
    EXPECT_NE(message.find("c.splatc"), std::string::npos) << message;
    EXPECT_NE(message.find("Gaussian 40"), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(dir_ / "c.splatc"));
}

TEST_F(CompactChunkTest, ACorruptBlockIsAnErrorAndTheOtherBlocksStillRead) {
    const SplatCloud cloud = chunk_cloud(20000, 0, 13, rule_);
    const sw::ChunkEntry e = write(cloud);
    const fs::path file = dir_ / "c.splatc";
    const std::vector<sw::BlockBytes> blocks = sw::record_block_bytes(file, e);
    ASSERT_EQ(blocks.size(), e.record_crc32.size());
    std::vector<std::uint8_t> bytes = engine::read_binary_file(file);
    bytes[blocks.back().offset + blocks.back().size / 2] ^= 0x10u;  // inside a zstd frame of the last block
    engine::write_file_atomic(file, bytes);
    const auto last = sw::record_blocks(e, 0, e.prefix_count[0]).back();
    const std::string message = error_of([&] { sw::read_chunk_range(file, e, last.begin, last.end); });
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    EXPECT_NE(message.find("checksum"), std::string::npos) << message;
    // The stream levels before it are untouched.
    const auto [begin, end] = sw::level_range(e, 4);
    ASSERT_LT(end, last.begin);
    EXPECT_EQ(sw::read_chunk_range(file, e, begin, end).size(), end - begin);

    // Blocks that match their checksums but do not decode (the manifest vouching for bad bytes) are
    // errors too, never a crash: ranges that are not finite, a plane table running past the block, a
    // zstd frame that is not one.
    const auto vouched_error = [&](std::size_t at, const std::vector<std::uint8_t>& values) {
        std::vector<std::uint8_t> bad = bytes;
        std::copy(values.begin(), values.end(), bad.begin() + static_cast<std::ptrdiff_t>(blocks.back().offset + at));
        engine::write_file_atomic(file, bad);
        sw::ChunkEntry vouched = e;
        vouched.record_crc32.back() = sw::checksum(std::span(bad).subspan(blocks.back().offset, blocks.back().size));
        return error_of([&] { sw::read_chunk_range(file, vouched, last.begin, last.end); });
    };
    using Damage = std::tuple<std::size_t, std::vector<std::uint8_t>, std::string>;
    for (const auto& [at, values, problem] : std::vector<Damage>{{0, {0x00, 0x00, 0xc0, 0x7f}, "not finite"},
                                                                 {76 + 3, {0x40}, "runs past"},
                                                                 {76 + 22 * 4, {0x00}, "zstd"}}) {
        const std::string bad = vouched_error(at, values);
        EXPECT_NE(bad.find(file.string()), std::string::npos) << bad;
        EXPECT_NE(bad.find("records ["), std::string::npos) << bad;
        EXPECT_NE(bad.find(problem), std::string::npos) << problem << ": " << bad;
    }
}

TEST_F(CompactChunkTest, TruncatedChangedOrForeignFilesAreErrorsNamingTheFile) {
    const SplatCloud cloud = chunk_cloud(5000, 0, 17, rule_);
    const sw::ChunkEntry e = write(cloud);
    const fs::path file = dir_ / "c.splatc";
    const std::vector<std::uint8_t> original = engine::read_binary_file(file);

    std::vector<std::uint8_t> bytes(original.begin(), original.end() - 100);
    engine::write_file_atomic(file, bytes);
    EXPECT_NE(error_of([&] { sw::read_chunk_range(file, e, 0, 1); }).find("truncated"), std::string::npos);

    bytes = original;
    bytes[sw::kCompactChunkFixedHeaderBytes] ^= 1u;  // the first block's size
    engine::write_file_atomic(file, bytes);
    EXPECT_NE(error_of([&] { sw::read_chunk_range(file, e, 0, 1); }).find("header does not match"), std::string::npos);

    // A header the manifest vouches for but that describes another file.
    sw::ChunkEntry lying = e;
    lying.header_crc32 = sw::checksum(std::span(bytes).first(e.header_bytes));
    EXPECT_NE(error_of([&] { sw::read_chunk_range(file, lying, 0, 1); }).find("header describes"), std::string::npos);

    const std::string other = "ply\nformat binary_little_endian 1.0\n";
    bytes.assign(original.size(), 0);
    std::copy(other.begin(), other.end(), bytes.begin());
    engine::write_file_atomic(file, bytes);
    lying.header_crc32 = sw::checksum(std::span(bytes).first(e.header_bytes));
    const std::string foreign = error_of([&] { sw::read_chunk_range(file, lying, 0, 1); });
    EXPECT_NE(foreign.find("not a compressed chunk file"), std::string::npos) << foreign;
    EXPECT_NE(foreign.find(file.string()), std::string::npos) << foreign;

    fs::remove(file);
    EXPECT_NE(error_of([&] { sw::read_chunk_range(file, e, 0, 1); }).find(file.string()), std::string::npos);
}

TEST_F(CompactChunkTest, HeaderRejectsOtherVersionsAndBlockSizes) {
    sw::CompactChunkHeader h;
    h.count = 5000;
    h.prefix_count = {5000, 3000, 3000, 10};
    h.block_bytes = {100, 200};
    std::vector<std::uint8_t> bytes = sw::encode_compact_chunk_header(h);
    EXPECT_EQ(bytes.size(), h.header_bytes());
    const sw::CompactChunkHeader back = sw::parse_compact_chunk_header(bytes, "h");
    EXPECT_EQ(back.count, 5000u);
    EXPECT_EQ(back.block_bytes, h.block_bytes);
    EXPECT_EQ(back.version, sw::kCompactChunkVersion);
    std::vector<std::uint8_t> version = bytes;
    version[8] = 1;  // the first version is still read
    EXPECT_EQ(sw::parse_compact_chunk_header(version, "h").version, 1u);
    for (const std::uint8_t v : {0, 3}) {
        version[8] = v;
        EXPECT_NE(error_of([&] { sw::parse_compact_chunk_header(version, "h"); }).find("version " + std::to_string(v)),
                  std::string::npos);
    }
    std::vector<std::uint8_t> block = bytes;
    block[24] = 7;
    EXPECT_NE(error_of([&] { sw::parse_compact_chunk_header(block, "h"); }).find("records per block"),
              std::string::npos);
    std::vector<std::uint8_t> degree = bytes;
    degree[12] = 4;
    EXPECT_NE(error_of([&] { sw::parse_compact_chunk_header(degree, "h"); }).find("SH degree"), std::string::npos);
    std::vector<std::uint8_t> counts = bytes;
    counts[47] = 0x01;  // prefix_count[1] above prefix_count[0]
    EXPECT_NE(error_of([&] { sw::parse_compact_chunk_header(counts, "h"); }).find("prefix counts"), std::string::npos);
    EXPECT_EQ(sw::parse_compact_chunk_header(bytes, "h").prefix_count, h.prefix_count);
    bytes.pop_back();
    EXPECT_NE(error_of([&] { sw::parse_compact_chunk_header(bytes, "h"); }).find("table"), std::string::npos);
    EXPECT_NE(error_of([&] { sw::parse_compact_chunk_header(std::span(bytes).first(10), "h"); }).find("shorter"),
              std::string::npos);
}

TEST_F(CompactChunkTest, PlyAndCompactFilesOfOneCloudDrawTheSameLevels) {
    const SplatCloud cloud = chunk_cloud(3000, 0, 19, rule_);
    const sw::ChunkEntry compact = write(cloud);
    const sw::ChunkEntry ply = sw::write_chunk_file(cloud, dir_, "c.lod.ply", {1, -2}, rule_, sw::ChunkCodec::ply);
    EXPECT_EQ(ply.codec, sw::ChunkCodec::ply);
    EXPECT_EQ(compact.prefix_count, ply.prefix_count);
    EXPECT_LT(compact.file_bytes * 3, ply.file_bytes);
    for (std::size_t l = 0; l < sw::kLevels; ++l) EXPECT_GE(compact.levels[l].extent_max, ply.levels[l].extent_max);
    EXPECT_EQ(sw::read_chunk_range(dir_ / "c.lod.ply", ply, 0, ply.prefix_count[0]).size(), cloud.size());
}

}  // namespace

// A version-1 file (a byte per higher SH coefficient), kept in tests/data as the generator wrote it:
// 1500 Gaussians at SH degree 1 over several blocks (splat_io_test::make_cloud(1500, 1, 15, true) in
// stream order). It still reads, each coefficient within half of version 1's step (its block's
// largest magnitude of the band / 127), which version 2's decoding of the same bytes would not give.
TEST(CompactChunkVersion1, StillReads) {
    ENGINE_REQUIRE_DATA("worlds/compact_chunk_v1_1500_sh1.splatc");
    const fs::path file = engine::test::data_file("worlds/compact_chunk_v1_1500_sh1.splatc");
    const std::vector<std::uint8_t> bytes = engine::read_binary_file(file);
    ASSERT_EQ(sw::parse_compact_chunk_header(std::span(bytes).first(sw::kCompactChunkFixedHeaderBytes +
                                                                    4 * sw::compact_chunk_block_count(bytes, "v1")),
                                             "v1")
                  .version,
              1u);
    const sw::StreamLevelRule rule;
    SplatCloud expected = splat_io_test::make_cloud(1500, 1, 15, true);
    expected = expected.permuted(sw::stream_order(expected, rule));
    const SplatCloud back = sw::read_compact_chunk_file(file);
    ASSERT_EQ(back.size(), expected.size());
    ASSERT_EQ(back.sh_degree, 1);
    float band_max = 0.0f;
    for (const float v : expected.sh_rest) band_max = std::max(band_max, std::abs(v));
    for (std::size_t i = 0; i < back.size(); ++i) {
        EXPECT_NEAR(back.positions[i].x, expected.positions[i].x, 1e-3f) << i;
        for (int k = 1; k <= 3; ++k)
            for (int c = 0; c < 3; ++c)
                ASSERT_LE(std::abs(back.sh_rest_at(i, k, c) - expected.sh_rest_at(i, k, c)),
                          0.5f * band_max / 127.0f * 1.001f)
                    << "Gaussian " << i << " coefficient " << k;
    }
}
