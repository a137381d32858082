#include "engine/gl/radix_sort.h"

#include <algorithm>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "compute_job.h"
#include "engine/core/error.h"
#include "engine/gl/buffer_texture.h"
#include "engine/gpu_sort_shared.h"

namespace engine::gl {
namespace {

static_assert(sizeof(SortParams) == 32, "SortParams is 32 bytes in std430");
static_assert(offsetof(SortParams, histogram_count) == 24 && offsetof(SortParams, histogram_total) == 28);
static_assert(SORT_RADIX_SIZE == 1 << SORT_RADIX_BITS);
static_assert(32 % SORT_RADIX_BITS == 0, "a digit must not straddle the low and high key words");
static_assert(SORT_WORKGROUP_SIZE % 32 == 0, "the scatter keeps one 32-bit lane mask word per 32 invocations");
static_assert((2 * SORT_RADIX_SIZE * SORT_MASK_WORDS + SORT_RADIX_SIZE) * 4 <= 32768,
              "the scatter's shared memory must fit the GL minimum of 32 KiB");

constexpr std::uint32_t max_groups = 65535;  // GL_MAX_COMPUTE_WORK_GROUP_COUNT guarantees this
constexpr GLbitfield results_visible =
    GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT;

const char* const error_prefix = "engine::gl::RadixSort::record(): ";

using detail::set_uint;

std::uint32_t tiles_for(std::uint32_t count) {
    return (count + SORT_TILE_SIZE - 1) / SORT_TILE_SIZE;
}

void check_job(const SortJob& job) {
    const auto fail = [](const std::string& message) { engine::fail(error_prefix + message); };
    detail::check_word(job.count_buffer, job.count_offset, error_prefix, "count");
    if (job.hi_bits > 32) fail("hi_bits " + std::to_string(job.hi_bits) + " exceeds the 32 bits of the high word");
    if (job.max_count > RadixSort::max_sort_count())
        fail("max_count " + std::to_string(job.max_count) + " exceeds the limit " +
             std::to_string(RadixSort::max_sort_count()));
    if (job.key_words != 1 && job.key_words != 2)
        fail("key_words " + std::to_string(job.key_words) + " is neither 1 nor 2");
    if (job.key_words == 1 && job.hi_bits != 0)
        fail("hi_bits " + std::to_string(job.hi_bits) + " with one-word keys, which have no high word");
    if (!job.keys || job.keys.size() < std::size_t{job.max_count} * 4 * job.key_words)
        fail("keys buffer of " + std::to_string(job.keys.size()) + " bytes is smaller than max_count " +
             std::to_string(job.max_count) + (job.key_words == 1 ? " uint keys" : " uvec2 keys"));
    if (!job.values || job.values.size() < std::size_t{job.max_count} * 4)
        fail("values buffer of " + std::to_string(job.values.size()) + " bytes is smaller than max_count " +
             std::to_string(job.max_count) + " uint values");
}

// A GPU timer span when timers are given, nothing otherwise.
class OptionalSpan {
public:
    OptionalSpan(GpuTimers* timers, const std::string& name) {
        if (timers != nullptr) scope_.emplace(*timers, name);
    }

private:
    std::optional<GpuTimerScope> scope_;
};

}  // namespace

RadixSort::RadixSort(ShaderLibrary& shaders) : shaders_(shaders), scan_(shaders) {}

std::uint32_t RadixSort::max_sort_count() {
    return std::min<std::uint32_t>(max_groups * SORT_TILE_SIZE,
                                   PrefixScan::max_scan_count() / SORT_RADIX_SIZE * SORT_TILE_SIZE);
}

std::uint32_t RadixSort::pass_count(std::uint32_t hi_bits) {
    return (32 + hi_bits + SORT_RADIX_BITS - 1) / SORT_RADIX_BITS;
}

void RadixSort::record(const SortJob& job, GpuTimers* timers) {
    check_job(job);
    const OptionalSpan total_span(timers, "radix_sort");
    texel_reads_ = job.texel_reads;
    key_words_ = job.key_words;
    prepare_buffers(job.max_count, job.key_words);
    // The keys, values and count were written by earlier passes.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    {
        const OptionalSpan stage(timers, "radix_sort.arguments");
        record_arguments(job);
    }
    const std::uint32_t passes = pass_count(job.hi_bits);
    for (std::uint32_t index = 0; index < passes; ++index) record_pass(job, index, timers);
    // Passes alternate caller -> swap -> caller; after an odd number the result is in the swap.
    if (passes % 2 == 1) {
        const OptionalSpan stage(timers, "radix_sort.copy");
        record_copy({keys_swap_, values_swap_}, {job.keys, job.values});
    }
    glMemoryBarrier(results_visible);
}

// Internal buffers follow the job's capacity: made anew at its size when it changes (whole 16 bytes).
void RadixSort::prepare_buffers(std::uint32_t max_count, std::uint32_t key_words) {
    max_count_ = max_count;
    const auto fit = [](Buffer& buffer, std::size_t bytes, const char* label) {
        if (buffer && buffer.size() >= bytes && buffer.size() < bytes + 16) return;
        buffer = Buffer(NoCreate);
        buffer.ensure_size(bytes, label);
    };
    params_.ensure_size(sizeof(SortParams), "radix_sort params");
    fit(histogram_, std::size_t{SORT_RADIX_SIZE} * tiles_for(max_count) * 4, "radix_sort histogram");
    fit(keys_swap_, std::size_t{max_count} * 4 * key_words, "radix_sort keys swap");
    fit(values_swap_, std::size_t{max_count} * 4, "radix_sort values swap");
}

std::uint64_t RadixSort::bytes() const {
    return params_.size() + histogram_.size() + keys_swap_.size() + values_swap_.size() + scan_.bytes();
}

void RadixSort::record_arguments(const SortJob& job) {
    detail::record_dispatch_arguments(shaders_.program({"engine/radix_sort_dispatch_args.comp.glsl"}), job.count_buffer,
                                      job.count_offset, job.max_count, SORT_BINDING_COUNT, params_,
                                      SORT_BINDING_PARAMS);
}

// One stable counting pass on one digit: histogram per tile, scan of all (digit, tile) counts,
// scatter. Even passes read the caller's buffers and write the swap buffers, odd passes the reverse.
void RadixSort::record_pass(const SortJob& job, std::uint32_t index, GpuTimers* timers) {
    const std::uint32_t total_bits = 32 + job.hi_bits;
    const std::uint32_t first_bit = index * SORT_RADIX_BITS;
    const Pass pass{first_bit / 32, first_bit % 32, std::min<std::uint32_t>(SORT_RADIX_BITS, total_bits - first_bit)};
    const Pair caller{job.keys, job.values};
    const Pair swap{keys_swap_, values_swap_};
    const Pair& in = index % 2 == 0 ? caller : swap;
    const Pair& out = index % 2 == 0 ? swap : caller;
    const std::string name = "radix_sort.pass" + std::to_string(index);
    {
        const OptionalSpan stage(timers, name + ".histogram");
        record_histogram(pass, in);
    }
    {
        const OptionalSpan stage(timers, name + ".scan");
        scan_.record({.values = histogram_,
                      .count_buffer = params_,
                      .count_offset = offsetof(SortParams, histogram_count),
                      .max_count = SORT_RADIX_SIZE * tiles_for(max_count_),
                      .total_buffer = params_,
                      .total_offset = offsetof(SortParams, histogram_total)});
    }
    const OptionalSpan stage(timers, name + ".scatter");
    record_scatter(pass, in, out);
}

void RadixSort::record_histogram(const Pass& pass, const Pair& in) {
    const auto& program = this->program("radix_sort_histogram.comp.glsl");
    glUseProgram(program.id());
    set_uint(program, "u_word", pass.word);
    set_uint(program, "u_shift", pass.shift);
    set_uint(program, "u_digit_bits", pass.bits);
    bind_pairs(in, in);
    dispatch_tiles();
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void RadixSort::record_scatter(const Pass& pass, const Pair& in, const Pair& out) {
    const auto& program = this->program("radix_sort_scatter.comp.glsl");
    glUseProgram(program.id());
    set_uint(program, "u_word", pass.word);
    set_uint(program, "u_shift", pass.shift);
    set_uint(program, "u_digit_bits", pass.bits);
    bind_pairs(in, out);
    dispatch_tiles();
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void RadixSort::record_copy(const Pair& in, const Pair& out) {
    const auto& program = this->program("radix_sort_copy.comp.glsl");
    glUseProgram(program.id());
    bind_pairs(in, out);
    dispatch_tiles();
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

const Program& RadixSort::program(const char* file) const {
    std::vector<std::string> defines;
    if (texel_reads_) defines.push_back("SORT_TEXEL_READS");
    if (key_words_ == 1) defines.push_back("SORT_ONE_WORD_KEYS");
    return shaders_.program({std::string("engine/") + file}, defines);
}

void RadixSort::bind_pairs(const Pair& in, const Pair& out) {
    if (texel_reads_) {
        bind_buffer_texture(key_texels_, "radix_sort key texels", key_words_ == 1 ? GL_R32UI : GL_RG32UI, in.keys,
                            SORT_TEXTURE_KEYS_IN);
        bind_buffer_texture(value_texels_, "radix_sort value texels", GL_R32UI, in.values, SORT_TEXTURE_VALUES_IN);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);  // written through storage buffers, read as texels
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SORT_BINDING_KEYS_IN, in.keys.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SORT_BINDING_VALUES_IN, in.values.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SORT_BINDING_KEYS_OUT, out.keys.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SORT_BINDING_VALUES_OUT, out.values.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SORT_BINDING_HISTOGRAM, histogram_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SORT_BINDING_PARAMS, params_.id());
}

// One workgroup per tile of the real count, sized on the GPU by radix_sort_dispatch_args.
void RadixSort::dispatch_tiles() {
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, params_.id());
    glDispatchComputeIndirect(static_cast<GLintptr>(offsetof(SortParams, dispatch)));
}

}  // namespace engine::gl
