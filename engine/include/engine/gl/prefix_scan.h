#pragma once
// GPU exclusive prefix scan of a uint buffer, in place, whose length lives in a GPU buffer (an
// earlier pass wrote it; the CPU never reads it back inside a frame). Reduce-then-scan over
// levels of block sums: any length up to max_scan_count().
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/gl/gpu_timers.h"
#include "engine/gl/objects.h"
#include "engine/gl/shader_library.h"

namespace engine::gl {

struct ScanJob {
    Buffer& values;                // scanned in place: values[i] = sum of values[0, i)
    const Buffer& count_buffer;    // holds the element count as a uint ...
    std::size_t count_offset = 0;  // ... at this byte offset (a multiple of 4)
    std::uint32_t max_count = 0;   // capacity; a larger count on the GPU is clamped
    Buffer& total_buffer;          // receives the sum of all counted elements ...
    std::size_t total_offset = 0;  // ... at this byte offset (a multiple of 4)
};

class PrefixScan {
public:
    // Programs come from `shaders`, which must outlive this object.
    explicit PrefixScan(ShaderLibrary& shaders);

    // Records the scan; elements at and beyond the count stay untouched. Ends with a barrier
    // that makes the results visible to shaders, indirect commands and buffer reads. Spans named
    // "prefix_scan*" go to `timers` when given. Throws engine::Error for buffers too small,
    // misaligned offsets or a max_count above max_scan_count().
    void record(const ScanJob& job, GpuTimers* timers = nullptr);

    // The largest max_count: indirect dispatches are limited to 65535 workgroups per dimension.
    static std::uint32_t max_scan_count();
    // GPU bytes of its own buffers (the levels and the block sums of the largest max_count so far).
    std::uint64_t bytes() const { return levels_.size() + block_sums_.size(); }

private:
    struct Level {
        std::uint32_t max_count = 0;    // elements at this level for the capacity
        std::uint32_t sums_offset = 0;  // where its block sums start in block_sums_
    };
    std::vector<Level> plan_levels(std::uint32_t max_count);
    void record_arguments(const ScanJob& job);
    void record_upsweep(const ScanJob& job, const std::vector<Level>& levels);
    void record_top(const ScanJob& job, const std::vector<Level>& levels);
    void record_downsweep(const ScanJob& job, const std::vector<Level>& levels);
    void bind_level(const Program& program, const ScanJob& job, std::size_t level, const std::vector<Level>& levels);

    ShaderLibrary& shaders_;
    Buffer levels_{NoCreate};      // ScanLevel[SCAN_MAX_LEVELS], GPU-written
    Buffer block_sums_{NoCreate};  // every level above the first, packed
};

}  // namespace engine::gl
