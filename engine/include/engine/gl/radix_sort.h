#pragma once
// GPU stable LSD radix sort of 64-bit (tile, depth) keys, or 32-bit keys, with uint values. The element count
// lives in a GPU buffer (written by an earlier pass, never read back by the CPU inside a frame);
// every dispatch is indirect, sized on the GPU from that count, so work follows the real count
// while the CPU only knows the capacity.
#include <cstddef>
#include <cstdint>

#include "engine/gl/gpu_timers.h"
#include "engine/gl/objects.h"
#include "engine/gl/prefix_scan.h"
#include "engine/gl/shader_library.h"

namespace engine::gl {

struct SortJob {
    // uvec2 per element: x = low word (bits of a positive float depth, which order like the
    // value), y = high word (tile index, below 2^hi_bits). Sorted ascending by (y, x) in place.
    Buffer& keys;
    Buffer& values;                // uint per element, moved along with its key
    const Buffer& count_buffer;    // holds the element count as a uint ...
    std::size_t count_offset = 0;  // ... at this byte offset (a multiple of 4)
    std::uint32_t max_count = 0;   // capacity; a larger count on the GPU is clamped
    // Significant bits of the high word, 0..32: ceil(log2(tile_count)). Higher bits are ignored.
    std::uint32_t hi_bits = 0;
    // 2: the uvec2 keys above; 1: one uint per key (the low word alone, all 32 bits sorted; hi_bits
    // must be 0), half the bytes of the keys and of the sort's own copy of them.
    std::uint32_t key_words = 2;
    // Read the input keys and values through buffer textures instead of storage loads (faster on CPU
    // drivers; the caller checks that max_count texels fit the driver's buffer textures). Same result.
    bool texel_reads = false;
};

class RadixSort {
public:
    // Programs come from `shaders`, which must outlive this object.
    explicit RadixSort(ShaderLibrary& shaders);

    // Records the sort. Stable: equal keys keep their input order. The result is in job.keys and
    // job.values; elements at and beyond the count stay untouched. Ends with a barrier that makes
    // the results visible to shaders, indirect commands and buffer reads. Spans "radix_sort*" go
    // to `timers` when given. Throws engine::Error for buffers too small, misaligned offsets,
    // hi_bits above 32 or max_count above max_sort_count().
    void record(const SortJob& job, GpuTimers* timers = nullptr);

    // The largest max_count: indirect dispatches are limited to 65535 workgroups per dimension.
    static std::uint32_t max_sort_count();
    // GPU bytes of its own buffers (the ping-pong partners, histograms, its scan's), which follow the
    // latest job's max_count: made anew at its size when it changes.
    std::uint64_t bytes() const;
    // Digit passes for `hi_bits`: all 32 low bits plus hi_bits, SORT_RADIX_BITS at a time.
    static std::uint32_t pass_count(std::uint32_t hi_bits);

private:
    struct Pass {
        std::uint32_t word = 0;   // 0: low word, 1: high word
        std::uint32_t shift = 0;  // first bit of the digit in that word
        std::uint32_t bits = 0;   // digit width
    };
    struct Pair {
        const Buffer& keys;
        const Buffer& values;
    };
    void prepare_buffers(std::uint32_t max_count, std::uint32_t key_words);
    void record_arguments(const SortJob& job);
    void record_pass(const SortJob& job, std::uint32_t index, GpuTimers* timers);
    void record_histogram(const Pass& pass, const Pair& in);
    void record_scatter(const Pass& pass, const Pair& in, const Pair& out);
    void record_copy(const Pair& in, const Pair& out);
    void bind_pairs(const Pair& in, const Pair& out);
    const Program& program(const char* file) const;
    void dispatch_tiles();

    ShaderLibrary& shaders_;
    PrefixScan scan_;
    std::uint32_t max_count_ = 0;
    bool texel_reads_ = false;     // the current job's SortJob::texel_reads
    std::uint32_t key_words_ = 2;  // and its SortJob::key_words
    Texture key_texels_{NoCreate}, value_texels_{NoCreate};
    Buffer params_{NoCreate};       // SortParams, GPU-written
    Buffer histogram_{NoCreate};    // per-tile digit counts, then offsets
    Buffer keys_swap_{NoCreate};    // ping-pong partner of job.keys
    Buffer values_swap_{NoCreate};  // ping-pong partner of job.values
};

}  // namespace engine::gl
