// Hostile SPZ input: truncation at many offsets, lying header fields and table of contents,
// unknown versions, broken gzip/zstd streams and decompression bombs. Every failure must be an
// engine::Error that starts with the file name (and, where it helps, the byte offset).
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "engine/core/file_io.h"
#include "splat_io_test_helpers.h"
#include "splat_lod/core/splat_io.h"
#include "test_support.h"

using splat_io_test::error_of;
using splat_io_test::make_cloud;
using splat_io_test::spz_v4_file;

namespace {

using Bytes = std::vector<std::uint8_t>;

std::string spz_error(const Bytes& bytes, const std::string& name = "h.spz") {
    return error_of([&] { splat_lod::read_spz(bytes, name); });
}

void expect_error(const std::string& error, const std::string& fragment, const std::string& name = "h.spz") {
    EXPECT_EQ(error.rfind(name + ": ", 0), 0u) << "message must start with the file name: " << error;
    EXPECT_NE(error.find(fragment), std::string::npos) << "expected \"" << fragment << "\" in: " << error;
}

Bytes with_u32(Bytes bytes, std::size_t offset, std::uint32_t value) {
    for (int k = 0; k < 4; ++k)
        bytes[offset + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(value >> (8 * k));
    return bytes;
}

Bytes with_u64(Bytes bytes, std::size_t offset, std::uint64_t value) {
    for (int k = 0; k < 8; ++k)
        bytes[offset + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(value >> (8 * k));
    return bytes;
}

std::uint64_t u64_at(const Bytes& bytes, std::size_t offset) {
    std::uint64_t v = 0;
    for (int k = 7; k >= 0; --k) v = v << 8 | bytes[offset + static_cast<std::size_t>(k)];
    return v;
}

}  // namespace

TEST(SplatIoHostileSpz, TruncatedBikerFailsAtEveryCut) {
    ENGINE_REQUIRE_SHARED_DATA();
    const Bytes biker = engine::read_binary_file(splat_io_test::real_splat("playcanvas-engine/biker.spz"));
    for (std::size_t cut : {0ul, 1ul, 3ul, 4ul, 15ul, 16ul, 31ul, 32ul, 40ul, 111ul, 112ul, 113ul, 5000ul,
                            biker.size() / 2, biker.size() - 1}) {
        SCOPED_TRACE("cut at " + std::to_string(cut));
        const std::string error = spz_error(Bytes(biker.begin(), biker.begin() + static_cast<long>(cut)), "biker.spz");
        EXPECT_EQ(error.rfind("biker.spz: ", 0), 0u) << error;
    }
    // The first stream's frame is cut: the message gives the stream's offset.
    const Bytes cut = Bytes(biker.begin(), biker.begin() + 50000);
    expect_error(spz_error(cut, "biker.spz"), "offset 112: zstd stream 0 needs 793872 bytes", "biker.spz");
}

TEST(SplatIoHostileSpz, LyingV4HeaderAndTableOfContents) {
    ENGINE_REQUIRE_SHARED_DATA();
    const Bytes biker = engine::read_binary_file(splat_io_test::real_splat("playcanvas-engine/biker.spz"));
    expect_error(spz_error(with_u32(biker, 4, 5)), "offset 4: unknown SPZ version 5");
    expect_error(spz_error(with_u32(biker, 4, 0)), "unknown SPZ version 0");
    expect_error(spz_error(with_u32(biker, 4, 1)), "version 1 (float16 positions) is not supported");
    expect_error(spz_error(with_u32(biker, 8, 152747)), "offset 40: stream 0 claims 1374714 bytes");
    expect_error(spz_error(with_u32(biker, 8, 0xffffffffu)), "stream 0 claims");
    Bytes bad = biker;
    bad[12] = 4;  // SH degree 4
    expect_error(spz_error(bad), "SH degree 4 is not supported");
    bad = biker;
    bad[12] = 3;  // SH degree 3 needs a sixth stream
    expect_error(spz_error(bad), "declares 5 streams, expected 6");
    bad = biker;
    bad[15] = 200;
    expect_error(spz_error(bad), "declares 200 streams");
    expect_error(spz_error(with_u32(biker, 16, 16)), "table of contents offset 16 < 32");
    expect_error(spz_error(with_u32(biker, 16, 0xfffffff0u)), "offset 4294967280: SPZ v4 table of contents needs");
    expect_error(spz_error(with_u64(biker, 32, ~0ull)), "zstd stream 0 needs 18446744073709551615 bytes");
    // Stream 1's frame shortened by 100 bytes in the table: stream 1 is then truncated.
    const std::uint64_t stream1 = u64_at(biker, 48);
    expect_error(spz_error(with_u64(biker, 48, stream1 - 100)), "zstd stream truncated");
    // The first frame's magic number corrupted.
    bad = biker;
    bad[112] ^= 0xff;
    expect_error(spz_error(bad), "offset 112: corrupt zstd stream");
}

TEST(SplatIoHostileSpz, ZstdStreamsThatExpandToTheWrongSize) {
    const std::uint32_t n = 10;
    const std::vector<Bytes> honest = {Bytes(9 * n), Bytes(n), Bytes(3 * n), Bytes(3 * n), Bytes(4 * n, 0)};
    EXPECT_EQ(splat_lod::read_spz(spz_v4_file(n, 0, honest), "ok.spz").size(), n);
    // A 1 MB stream of zeros where the header allows 90 bytes: stopped, never buffered whole.
    std::vector<Bytes> bomb = honest;
    bomb[0] = Bytes(1 << 20);
    expect_error(spz_error(spz_v4_file(n, 0, bomb, {9 * n})), "expands to more than the 90 bytes expected");
    std::vector<Bytes> short_stream = honest;
    short_stream[2] = Bytes(3 * n - 1);
    expect_error(spz_error(spz_v4_file(n, 0, short_stream, {9 * n, n, 3 * n})), "expands to 29 bytes, expected 30");
}

TEST(SplatIoHostileSpz, TruncatedAndCorruptGzipStreams) {
    const Bytes v3 = splat_io_test::encode_spz(make_cloud(2000, 2, 5), 3);
    for (std::size_t cut : {0ul, 1ul, 2ul, 10ul, 30ul, 100ul, v3.size() / 2, v3.size() - 9, v3.size() - 1}) {
        SCOPED_TRACE("cut at " + std::to_string(cut));
        const std::string error = spz_error(Bytes(v3.begin(), v3.begin() + static_cast<long>(cut)), "v3.spz");
        EXPECT_EQ(error.rfind("v3.spz: ", 0), 0u) << error;
    }
    expect_error(spz_error(Bytes(v3.begin(), v3.begin() + static_cast<long>(v3.size() / 2))), "gzip stream truncated");
    Bytes bad = v3;
    bad[2] = 7;  // compression method other than deflate
    expect_error(spz_error(bad), "corrupt gzip stream");
    bad = v3;
    for (std::size_t i = v3.size() / 2; i < v3.size() / 2 + 16; ++i) bad[i] ^= 0x5a;
    expect_error(spz_error(bad), "h.spz: ");
}

TEST(SplatIoHostileSpz, LyingLegacyHeaders) {
    const Bytes payload = splat_io_test::encode_spz(make_cloud(100, 1, 6), 3, false);
    EXPECT_EQ(splat_lod::read_spz(payload, "raw.spz").size(), 100u) << "an un-gzipped v3 payload is accepted";
    splat_lod::LoadReport report;
    Bytes antialiased = payload;
    antialiased[14] = 1;
    splat_lod::read_spz(antialiased, "aa.spz", &report);
    EXPECT_TRUE(report.antialiased);
    EXPECT_EQ(splat_lod::read_spz(splat_io_test::gzip(payload), "v3.spz").size(), 100u);
    expect_error(spz_error(splat_io_test::gzip(with_u32(payload, 4, 7))), "unknown SPZ version 7");
    expect_error(spz_error(splat_io_test::gzip(with_u32(payload, 4, 4))), "SPZ version 4 inside a gzip stream");
    expect_error(spz_error(splat_io_test::gzip(with_u32(payload, 8, 101))), "Gaussians need");
    expect_error(spz_error(splat_io_test::gzip(with_u32(payload, 8, 0xffffffffu))), "(truncated)");
    expect_error(spz_error(splat_io_test::gzip(Bytes(payload.begin(), payload.begin() + 10))),
                 "no complete SPZ header");
    expect_error(spz_error(Bytes{'N', 'O', 'P', 'E', 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}), "offset 0: not an SPZ file");
    // A gzip bomb: 8 MB of zeros behind a header for one Gaussian is cut off at the bound
    // (header + arrays + 1 MiB for extensions).
    Bytes bomb = with_u32(payload, 8, 1);
    bomb.resize(8u << 20, 0);
    expect_error(spz_error(splat_io_test::gzip(bomb)), "bytes the header allows");
}
