#include "decompress.h"

#include <algorithm>
#include <array>
#include <limits>
#include <memory>

#include <zlib.h>
#include <zstd.h>

#include "io_util.h"

namespace splat_lod::io {
namespace {

constexpr std::size_t kChunk = 64 * 1024;

// zlib counts input in uInt; feed it at most this much per call.
constexpr std::size_t kMaxZlibInput = std::numeric_limits<uInt>::max();

struct InflateGuard {
    z_stream* stream;
    ~InflateGuard() { inflateEnd(stream); }
};

struct ZstdStreamDeleter {
    void operator()(ZSTD_DStream* s) const { ZSTD_freeDStream(s); }
};

void append_limited(std::vector<std::uint8_t>& out, const std::uint8_t* data, std::size_t size,
                    std::uint64_t max_output) {
    const std::size_t room = static_cast<std::size_t>(max_output - std::min<std::uint64_t>(out.size(), max_output));
    out.insert(out.end(), data, data + std::min(size, room));
}

}  // namespace

std::vector<std::uint8_t> gunzip(std::span<const std::uint8_t> compressed, std::uint64_t max_output, bool stop_early,
                                 const std::string& name) {
    z_stream stream{};
    // 16 + MAX_WBITS: expect a gzip wrapper (header and CRC), as SPZ writes.
    if (inflateInit2(&stream, 16 + MAX_WBITS) != Z_OK) fail_file(name, "cannot initialise zlib");
    InflateGuard guard{&stream};
    std::vector<std::uint8_t> out;
    std::array<std::uint8_t, kChunk> buffer{};
    std::size_t consumed = 0;
    for (;;) {
        if (stream.avail_in == 0 && consumed < compressed.size()) {
            const std::size_t feed = std::min(compressed.size() - consumed, kMaxZlibInput);
            stream.next_in = const_cast<Bytef*>(compressed.data() + consumed);
            stream.avail_in = static_cast<uInt>(feed);
            consumed += feed;
        }
        stream.next_out = buffer.data();
        stream.avail_out = static_cast<uInt>(buffer.size());
        const int rc = inflate(&stream, Z_NO_FLUSH);
        const std::size_t produced = buffer.size() - stream.avail_out;
        if (rc != Z_OK && rc != Z_STREAM_END && rc != Z_BUF_ERROR) {
            const std::string why = stream.msg ? stream.msg : "error " + std::to_string(rc);
            fail_at(name, stream.total_in, "corrupt gzip stream (zlib: " + why + ")");
        }
        if (out.size() + produced > max_output) {
            append_limited(out, buffer.data(), produced, max_output);
            if (stop_early) return out;
            fail_at(name, stream.total_in,
                    "gzip stream expands to more than the " + std::to_string(max_output) + " bytes the header allows");
        }
        out.insert(out.end(), buffer.data(), buffer.data() + produced);
        if (rc == Z_STREAM_END) return out;
        if (produced == 0 && stream.avail_in == 0 && consumed == compressed.size())
            fail_at(name, stream.total_in, "gzip stream truncated");
    }
}

std::vector<std::uint8_t> unzstd(std::span<const std::uint8_t> compressed, std::uint64_t expected_size,
                                 std::uint64_t base_offset, const std::string& name) {
    std::unique_ptr<ZSTD_DStream, ZstdStreamDeleter> stream(ZSTD_createDStream());
    if (!stream) fail_file(name, "cannot initialise zstd");
    ZSTD_initDStream(stream.get());
    std::vector<std::uint8_t> out;
    std::array<std::uint8_t, kChunk> buffer{};
    ZSTD_inBuffer in{compressed.data(), compressed.size(), 0};
    std::size_t remaining_in_frame = 1;
    while (remaining_in_frame != 0) {
        ZSTD_outBuffer chunk{buffer.data(), buffer.size(), 0};
        remaining_in_frame = ZSTD_decompressStream(stream.get(), &chunk, &in);
        if (ZSTD_isError(remaining_in_frame))
            fail_at(name, base_offset + in.pos,
                    std::string("corrupt zstd stream (") + ZSTD_getErrorName(remaining_in_frame) + ")");
        if (out.size() + chunk.pos > expected_size)
            fail_at(name, base_offset,
                    "zstd stream expands to more than the " + std::to_string(expected_size) + " bytes expected");
        out.insert(out.end(), buffer.data(), buffer.data() + chunk.pos);
        if (remaining_in_frame != 0 && in.pos == in.size && chunk.pos < chunk.size)
            fail_at(name, base_offset + in.pos, "zstd stream truncated");
    }
    if (out.size() != expected_size)
        fail_at(name, base_offset,
                "zstd stream expands to " + std::to_string(out.size()) + " bytes, expected " +
                    std::to_string(expected_size));
    if (in.pos != in.size) fail_at(name, base_offset + in.pos, "unexpected bytes after the zstd frame");
    return out;
}

}  // namespace splat_lod::io
