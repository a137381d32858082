#include "engine/gl/prefix_scan.h"

#include <optional>
#include <string>

#include "compute_job.h"
#include "engine/core/error.h"
#include "engine/gpu_sort_shared.h"

namespace engine::gl {
namespace {

static_assert(sizeof(ScanLevel) == 16, "ScanLevel is 16 bytes in std430");
static_assert(SCAN_WORKGROUP_SIZE % 32 == 0, "the workgroup scan rakes with 32 invocations");
static_assert(SCAN_BLOCK_SIZE == SCAN_WORKGROUP_SIZE * SCAN_ELEMENTS_PER_THREAD);

constexpr std::uint32_t block_size = SCAN_BLOCK_SIZE;
constexpr std::uint32_t max_groups = 65535;  // GL_MAX_COMPUTE_WORK_GROUP_COUNT guarantees this
constexpr GLbitfield results_visible =
    GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT;

const char* const error_prefix = "engine::gl::PrefixScan::record(): ";

using detail::set_uint;

void check_job(const ScanJob& job) {
    detail::check_word(job.count_buffer, job.count_offset, error_prefix, "count");
    detail::check_word(job.total_buffer, job.total_offset, error_prefix, "total");
    if (job.max_count > PrefixScan::max_scan_count())
        engine::fail(std::string(error_prefix) + "max_count " + std::to_string(job.max_count) + " exceeds the limit " +
                     std::to_string(PrefixScan::max_scan_count()));
    if (!job.values || job.values.size() < std::size_t{job.max_count} * 4)
        engine::fail(std::string(error_prefix) + "values buffer of " + std::to_string(job.values.size()) +
                     " bytes is smaller than max_count " + std::to_string(job.max_count) + " uints");
}

}  // namespace

PrefixScan::PrefixScan(ShaderLibrary& shaders) : shaders_(shaders) {}

std::uint32_t PrefixScan::max_scan_count() {
    return max_groups * block_size;
}

// Level 0 is the caller's buffer; each further level holds the block sums of the one below, down
// to a level that fits one workgroup. Sizes follow the capacity; the GPU fills in real counts.
std::vector<PrefixScan::Level> PrefixScan::plan_levels(std::uint32_t max_count) {
    std::vector<Level> levels{{max_count, 0}};
    std::uint32_t sums_words = 0;
    while (levels.back().max_count > block_size) {
        levels.back().sums_offset = sums_words;
        const std::uint32_t next = (levels.back().max_count + block_size - 1) / block_size;
        sums_words += next;
        levels.push_back({next, 0});
    }
    if (levels.size() > SCAN_MAX_LEVELS) engine::fail(std::string(error_prefix) + "too many scan levels");
    levels_.ensure_size(sizeof(ScanLevel) * SCAN_MAX_LEVELS, "prefix_scan levels");
    block_sums_.ensure_size(std::size_t{sums_words} * 4, "prefix_scan block sums");
    return levels;
}

void PrefixScan::record(const ScanJob& job, GpuTimers* timers) {
    check_job(job);
    std::optional<GpuTimerScope> span;
    if (timers != nullptr) span.emplace(*timers, "prefix_scan");
    const std::vector<Level> levels = plan_levels(job.max_count);
    // The count and the values were written by earlier passes.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    record_arguments(job);
    record_upsweep(job, levels);
    record_top(job, levels);
    record_downsweep(job, levels);
    glMemoryBarrier(results_visible);
}

void PrefixScan::record_arguments(const ScanJob& job) {
    detail::record_dispatch_arguments(shaders_.program({"engine/prefix_scan_dispatch_args.comp.glsl"}),
                                      job.count_buffer, job.count_offset, job.max_count, SCAN_BINDING_COUNT, levels_,
                                      SCAN_BINDING_LEVELS);
}

// Binds level `level`'s data (the caller's buffer or a block-sum range), the block sums it
// reduces into or takes offsets from, and the GPU-written level table.
void PrefixScan::bind_level(const Program& program, const ScanJob& job, std::size_t level,
                            const std::vector<Level>& levels) {
    set_uint(program, "u_level", static_cast<std::uint32_t>(level));
    set_uint(program, "u_data_offset", level == 0 ? 0 : levels[level - 1].sums_offset);
    set_uint(program, "u_sums_offset", levels[level].sums_offset);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SCAN_BINDING_DATA, level == 0 ? job.values.id() : block_sums_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SCAN_BINDING_SUMS, block_sums_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SCAN_BINDING_LEVELS, levels_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SCAN_BINDING_TOTAL, job.total_buffer.id());
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, levels_.id());
}

void PrefixScan::record_upsweep(const ScanJob& job, const std::vector<Level>& levels) {
    const auto& program = shaders_.program({"engine/prefix_scan_reduce.comp.glsl"});
    glUseProgram(program.id());
    for (std::size_t level = 0; level + 1 < levels.size(); ++level) {
        bind_level(program, job, level, levels);
        glDispatchComputeIndirect(static_cast<GLintptr>(level * sizeof(ScanLevel)));
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
}

// The top level fits one workgroup by construction, whatever the real count.
void PrefixScan::record_top(const ScanJob& job, const std::vector<Level>& levels) {
    const auto& program = shaders_.program({"engine/prefix_scan_block.comp.glsl"});
    glUseProgram(program.id());
    bind_level(program, job, levels.size() - 1, levels);
    glProgramUniform1i(program.id(), glGetUniformLocation(program.id(), "u_add_block_offsets"), GL_FALSE);
    glProgramUniform1i(program.id(), glGetUniformLocation(program.id(), "u_write_total"), GL_TRUE);
    set_uint(program, "u_total_index", static_cast<std::uint32_t>(job.total_offset / 4));
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void PrefixScan::record_downsweep(const ScanJob& job, const std::vector<Level>& levels) {
    const auto& program = shaders_.program({"engine/prefix_scan_block.comp.glsl"});
    glUseProgram(program.id());
    glProgramUniform1i(program.id(), glGetUniformLocation(program.id(), "u_add_block_offsets"), GL_TRUE);
    glProgramUniform1i(program.id(), glGetUniformLocation(program.id(), "u_write_total"), GL_FALSE);
    for (std::size_t level = levels.size() - 1; level-- > 0;) {
        bind_level(program, job, level, levels);
        glDispatchComputeIndirect(static_cast<GLintptr>(level * sizeof(ScanLevel)));
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
}

}  // namespace engine::gl
