// Random byte mutations of small valid files in every binary format: a reader may accept the
// result or throw engine::Error, nothing else (run under ASan/UBSan to check memory safety too).
#include <functional>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "splat_io_test_helpers.h"
#include "splat_lod/core/splat_io.h"
#include "test_support.h"

using splat_io_test::make_cloud;

namespace {

using Bytes = std::vector<std::uint8_t>;
using Reader = std::function<void(const Bytes&)>;

// Mutates 1-4 bytes per trial, half of the trials inside the first `header` bytes where the
// counts, versions and offsets live. Returns how many mutants were rejected.
std::size_t mutate_and_read(const Bytes& original, std::size_t header, const Reader& read, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::size_t rejected = 0;
    for (int trial = 0; trial < 300; ++trial) {
        Bytes bytes = original;
        const int edits = 1 + static_cast<int>(rng() % 4);
        for (int e = 0; e < edits; ++e) {
            const std::size_t span = trial % 2 == 0 ? std::min(header, bytes.size()) : bytes.size();
            bytes[rng() % span] = static_cast<std::uint8_t>(rng());
        }
        try {
            read(bytes);
        } catch (const engine::Error& e) {
            ++rejected;
            EXPECT_EQ(std::string(e.what()).rfind("m: ", 0), 0u) << e.what();
        }
    }
    return rejected;
}

// Readers get a LoadReport so that accepted mutants do not log their warnings.
void read_ply(const Bytes& b) {
    splat_lod::LoadReport quiet;
    splat_lod::read_ply(b, "m", &quiet);
}

void read_spz(const Bytes& b) {
    splat_lod::LoadReport quiet;
    splat_lod::read_spz(b, "m", &quiet);
}

void read_splat(const Bytes& b) {
    splat_lod::LoadReport quiet;
    splat_lod::read_antimatter_splat(b, "m", &quiet);
}

}  // namespace

TEST(SplatIoMutation, InriaPly) {
    const Bytes bytes = splat_lod::encode_inria_ply(make_cloud(20, 1, 3, true, true));
    EXPECT_GT(mutate_and_read(bytes, 700, read_ply, 1), 0u);
}

TEST(SplatIoMutation, CompressedPly) {
    ENGINE_REQUIRE_DATA("splats/playcanvas-engine/test-fixture-64.compressed.ply");
    const Bytes bytes =
        engine::read_binary_file(splat_io_test::real_splat("playcanvas-engine/test-fixture-64.compressed.ply"));
    EXPECT_GT(mutate_and_read(bytes, 1500, read_ply, 2), 0u);
}

TEST(SplatIoMutation, Spz) {
    for (int version : {2, 3, 4}) {
        const Bytes bytes = splat_io_test::encode_spz(make_cloud(30, 2, 4), version);
        EXPECT_GT(mutate_and_read(bytes, 120, read_spz, 10u + static_cast<std::uint32_t>(version)), 0u) << version;
    }
    const Bytes raw = splat_io_test::encode_spz(make_cloud(30, 3, 4), 3, false);
    EXPECT_GT(mutate_and_read(raw, 16, read_spz, 20), 0u);
}

TEST(SplatIoMutation, AntimatterSplat) {
    // Every 32-byte multiple is a valid .splat: mutants are accepted or, with NaN, counted.
    const Bytes bytes = splat_lod::encode_antimatter_splat(make_cloud(10, 0, 5));
    EXPECT_EQ(mutate_and_read(bytes, 32, read_splat, 6), 0u);
}
