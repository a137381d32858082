// GPU radix sort and prefix scan against their CPU references (std::stable_sort, a sequential
// exclusive scan), bit for bit, with the element count coming from a GPU buffer.
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include <glm/glm.hpp>

#include "engine/core/error.h"
#include "engine/gl/gpu_timers.h"
#include "engine/gl/objects.h"
#include "engine/gl/prefix_scan.h"
#include "engine/gl/radix_sort.h"
#include "engine/gl/shader_library.h"
#include "engine/gpu_sort_shared.h"
#include "gpu_fixture.h"

namespace {

using engine::gl::Buffer;
using engine::gl::PrefixScan;
using engine::gl::RadixSort;

// One library for the whole binary: compiling the programs once keeps the file fast on llvmpipe.
// Fixtures reach it before SetUp(), so it asks for the GL context first: statics are destroyed in
// reverse order, and the programs must go while the context still exists.
engine::gl::ShaderLibrary& shader_library() {
    engine::test::gl_context();
    static engine::gl::ShaderLibrary library;  // the engine's own shaders: the sort and scan are engine programs
    return library;
}

template <class T>
Buffer make_buffer(const std::vector<T>& data, const char* label) {
    Buffer buffer(label);
    buffer.storage(data.size() * sizeof(T), data.empty() ? nullptr : data.data());
    return buffer;
}

template <class T>
std::vector<T> read_buffer(const Buffer& buffer, std::size_t count) {
    std::vector<T> data(count);
    if (count > 0) glGetNamedBufferSubData(buffer.id(), 0, static_cast<GLsizeiptr>(count * sizeof(T)), data.data());
    return data;
}

struct Element {
    glm::uvec2 key;  // x = depth bits, y = tile
    std::uint32_t value;
    bool operator==(const Element&) const = default;
};

std::uint64_t sort_key(const Element& e) {
    return (std::uint64_t{e.key.y} << 32) | e.key.x;
}

// Values are the input index, so a stability failure shows up as a value mismatch.
std::vector<Element> random_elements(std::size_t count, std::uint32_t hi_bits, std::uint32_t distinct_depths,
                                     std::uint32_t seed) {
    std::mt19937 rng(seed);
    const std::uint32_t hi_mask = hi_bits >= 32 ? ~0u : (1u << hi_bits) - 1u;
    std::uniform_int_distribution<std::uint32_t> depth_pick(0, distinct_depths - 1);
    std::vector<Element> elements(count);
    for (std::size_t i = 0; i < count; ++i) {
        const std::uint32_t depth = distinct_depths == 0 ? rng() : 0x3f000000u + depth_pick(rng) * 977u;
        elements[i] = {{depth, rng() & hi_mask}, static_cast<std::uint32_t>(i)};
    }
    return elements;
}

struct SortRun {
    std::uint32_t count = 0;      // what the GPU count buffer says
    std::uint32_t max_count = 0;  // the capacity the CPU knows
    std::uint32_t hi_bits = 0;
    bool texel_reads = false;     // SortJob::texel_reads
    std::uint32_t key_words = 2;  // SortJob::key_words (1: the low words alone, hi_bits 0)
};

// Sorts `elements` (max_count of them) on the GPU with the count in a GPU buffer at byte 8.
std::vector<Element> gpu_sort(RadixSort& sort, const std::vector<Element>& elements, const SortRun& run) {
    std::vector<glm::uvec2> keys(elements.size());
    std::vector<std::uint32_t> words(elements.size()), values(elements.size());
    for (std::size_t i = 0; i < elements.size(); ++i) {
        keys[i] = elements[i].key;
        words[i] = elements[i].key.x;
        values[i] = elements[i].value;
    }
    const bool one_word = run.key_words == 1;
    Buffer key_buffer = one_word ? make_buffer(words, "test keys") : make_buffer(keys, "test keys");
    Buffer value_buffer = make_buffer(values, "test values");
    const Buffer count_buffer = make_buffer(std::vector<std::uint32_t>{7u, 7u, run.count, 7u}, "test count");
    sort.record({.keys = key_buffer,
                 .values = value_buffer,
                 .count_buffer = count_buffer,
                 .count_offset = 8,
                 .max_count = run.max_count,
                 .hi_bits = run.hi_bits,
                 .key_words = run.key_words,
                 .texel_reads = run.texel_reads});
    if (one_word) {
        words = read_buffer<std::uint32_t>(key_buffer, elements.size());
        for (std::size_t i = 0; i < elements.size(); ++i) keys[i] = {words[i], 0u};
    } else {
        keys = read_buffer<glm::uvec2>(key_buffer, elements.size());
    }
    values = read_buffer<std::uint32_t>(value_buffer, elements.size());
    std::vector<Element> sorted(elements.size());
    for (std::size_t i = 0; i < elements.size(); ++i) sorted[i] = {keys[i], values[i]};
    return sorted;
}

// The first `count` elements stably sorted; the rest as they were.
std::vector<Element> cpu_sort(std::vector<Element> elements, std::uint32_t count) {
    std::stable_sort(elements.begin(), elements.begin() + count,
                     [](const Element& a, const Element& b) { return sort_key(a) < sort_key(b); });
    return elements;
}

::testing::AssertionResult same_elements(const std::vector<Element>& actual, const std::vector<Element>& expected) {
    if (actual.size() != expected.size()) return ::testing::AssertionFailure() << "sizes differ";
    for (std::size_t i = 0; i < actual.size(); ++i) {
        if (actual[i] == expected[i]) continue;
        return ::testing::AssertionFailure()
               << "first difference at " << i << ": got key (" << actual[i].key.y << ", " << actual[i].key.x
               << ") value " << actual[i].value << ", expected key (" << expected[i].key.y << ", " << expected[i].key.x
               << ") value " << expected[i].value;
    }
    return ::testing::AssertionSuccess();
}

class GpuSortTest : public engine::test::GpuTest {
protected:
    RadixSort sort{shader_library()};

    // Both ways of reading the input (storage loads and buffer textures) must give the stable order.
    void expect_sorted(const std::vector<Element>& elements, SortRun run) {
        const auto expected = cpu_sort(elements, std::min(run.count, run.max_count));
        for (const bool texel_reads : {false, true}) {
            run.texel_reads = texel_reads;
            EXPECT_TRUE(same_elements(gpu_sort(sort, elements, run), expected))
                << "count " << run.count << ", max_count " << run.max_count << ", hi_bits " << run.hi_bits
                << ", texel reads " << texel_reads;
        }
    }
    void expect_sorted(std::uint32_t count, std::uint32_t hi_bits, std::uint32_t distinct_depths, std::uint32_t seed) {
        expect_sorted(random_elements(count, hi_bits, distinct_depths, seed), {count, count, hi_bits});
    }
};

TEST_F(GpuSortTest, SortMatchesStableSortAcrossTileBoundaries) {
    constexpr std::uint32_t tile = SORT_TILE_SIZE;
    for (const std::uint32_t count : {0u, 1u, 2u, 255u, 256u, 257u, tile - 1, tile, tile + 1, 65537u})
        expect_sorted(count, 16, 5, count);
}

TEST_F(GpuSortTest, SortIsStableForManyEqualKeys) {
    expect_sorted(100000, 2, 3, 1);  // 12 distinct keys: long runs of equal keys across tiles
    expect_sorted(5000, 0, 1, 2);    // every key equal: the output is the input
}

TEST_F(GpuSortTest, SortHandlesEveryHighBitWidth) {
    // 0, 8, 16, 24 and 32 high bits give 4..8 passes: both even (result in place) and odd
    // (copied back) pass counts.
    for (const std::uint32_t hi_bits : {0u, 1u, 8u, 9u, 12u, 16u, 24u, 32u}) expect_sorted(20000, hi_bits, 0, hi_bits);
}

// One-word keys sort like two-word keys whose high word is 0, in half the bytes.
TEST_F(GpuSortTest, OneWordKeysSortLikeTheirLowWord) {
    for (const std::uint32_t count : {0u, 1u, 257u, std::uint32_t{SORT_TILE_SIZE} + 1, 70001u})
        expect_sorted(random_elements(count, 0, 0, count), {count, count, 0, false, 1});
    expect_sorted(random_elements(50000, 0, 7, 9), {50000, 50000, 0, false, 1});    // long runs of equal keys
    expect_sorted(random_elements(30000, 0, 40, 10), {20000, 30000, 0, false, 1});  // the rest untouched
}

TEST_F(GpuSortTest, SortHandlesAllDepthBitsSet) {
    auto elements = random_elements(10000, 16, 0, 3);
    for (std::size_t i = 0; i < elements.size(); i += 3) elements[i].key.x = 0xffffffffu;
    for (std::size_t i = 1; i < elements.size(); i += 7) elements[i].key = {0xffffffffu, 0xffffu};
    for (std::size_t i = 2; i < elements.size(); i += 11) elements[i].key.x = 0u;
    expect_sorted(elements, {10000, 10000, 16});
}

TEST_F(GpuSortTest, SortOfAMillionRandomKeysMatches) {
    expect_sorted(1000003, 16, 0, 4);
}

TEST_F(GpuSortTest, SortUsesTheGpuCountAndLeavesTheRestUntouched) {
    const auto elements = random_elements(100000, 12, 50, 5);
    expect_sorted(elements, {77777, 100000, 12});
    expect_sorted(elements, {0, 100000, 12});
    // A count above the capacity (a bad earlier pass) is clamped, never overflows.
    expect_sorted(elements, {5000000, 100000, 12});
}

TEST_F(GpuSortTest, SortReusesItsBuffersAcrossSizes) {
    expect_sorted(1000, 8, 10, 6);
    expect_sorted(70000, 16, 0, 7);
    expect_sorted(300, 3, 4, 8);
}

TEST_F(GpuSortTest, SortRecordsNamedGpuTimerSpans) {
    engine::gl::GpuTimers timers;
    auto elements = random_elements(4096, 4, 0, 9);
    std::vector<glm::uvec2> keys(elements.size());
    Buffer key_buffer = make_buffer(keys, "test keys");
    Buffer value_buffer = make_buffer(std::vector<std::uint32_t>(elements.size()), "test values");
    const Buffer count_buffer = make_buffer(std::vector<std::uint32_t>{4096u}, "test count");
    timers.begin_frame();
    sort.record(
        {.keys = key_buffer, .values = value_buffer, .count_buffer = count_buffer, .max_count = 4096, .hi_bits = 4},
        &timers);
    timers.end_frame();
    timers.wait_all();
    ASSERT_TRUE(timers.latest().has_value());
    const auto& spans = *timers.latest();
    const auto has = [&](const char* name) {
        return std::any_of(spans.begin(), spans.end(), [&](const auto& s) { return s.name == name; });
    };
    EXPECT_TRUE(has("radix_sort"));
    EXPECT_TRUE(has("radix_sort.pass0.scatter"));
    EXPECT_TRUE(has("radix_sort.copy"));  // 36 bits: five passes
}

TEST_F(GpuSortTest, SortRejectsInconsistentJobs) {
    Buffer keys = make_buffer(std::vector<glm::uvec2>(100), "test keys");
    Buffer values = make_buffer(std::vector<std::uint32_t>(100), "test values");
    const Buffer count = make_buffer(std::vector<std::uint32_t>{100u, 0u}, "test count");
    const auto job = [&](std::size_t count_offset, std::uint32_t max_count, std::uint32_t hi_bits,
                         std::uint32_t key_words = 2) {
        sort.record({.keys = keys,
                     .values = values,
                     .count_buffer = count,
                     .count_offset = count_offset,
                     .max_count = max_count,
                     .hi_bits = hi_bits,
                     .key_words = key_words});
    };
    EXPECT_THROW(job(2, 100, 8), engine::Error);     // misaligned count
    EXPECT_THROW(job(8, 100, 8), engine::Error);     // count outside its buffer
    EXPECT_THROW(job(0, 101, 8), engine::Error);     // buffers smaller than max_count
    EXPECT_THROW(job(0, 100, 33), engine::Error);    // more high bits than a word has
    EXPECT_THROW(job(0, 100, 8, 1), engine::Error);  // high bits with one-word keys
    EXPECT_THROW(job(0, 100, 0, 3), engine::Error);  // keys of three words
    EXPECT_NO_THROW(job(4, 100, 32));
    EXPECT_NO_THROW(job(4, 100, 0, 1));
}

// ---- Prefix scan ----

struct ScanResult {
    std::vector<std::uint32_t> values;
    std::vector<std::uint32_t> totals;
};

// Scans `values` with the count in a GPU buffer; the total goes to word 2 of a 4-word buffer.
ScanResult gpu_scan(PrefixScan& scan, const std::vector<std::uint32_t>& values, std::uint32_t count,
                    std::uint32_t max_count) {
    Buffer value_buffer = make_buffer(values, "test scan values");
    const Buffer count_buffer = make_buffer(std::vector<std::uint32_t>{count}, "test scan count");
    Buffer total_buffer = make_buffer(std::vector<std::uint32_t>(4, 0xdeadbeefu), "test scan total");
    scan.record({.values = value_buffer,
                 .count_buffer = count_buffer,
                 .max_count = max_count,
                 .total_buffer = total_buffer,
                 .total_offset = 8});
    return {read_buffer<std::uint32_t>(value_buffer, values.size()), read_buffer<std::uint32_t>(total_buffer, 4)};
}

class GpuScanTest : public engine::test::GpuTest {
protected:
    PrefixScan scan{shader_library()};

    // Scans `size` random values of which the GPU count covers `count`; checks the prefix, the
    // untouched tail and the total.
    void expect_scanned(std::uint32_t size, std::uint32_t count, std::uint32_t max_value = 15) {
        std::mt19937 rng(size);
        std::uniform_int_distribution<std::uint32_t> pick(0, max_value);
        std::vector<std::uint32_t> values(size);
        for (auto& v : values) v = pick(rng);
        std::vector<std::uint32_t> expected = values;
        const std::uint32_t counted = std::min(count, size);
        std::exclusive_scan(values.begin(), values.begin() + counted, expected.begin(), 0u);
        const std::uint32_t total = std::accumulate(values.begin(), values.begin() + counted, 0u);
        const ScanResult result = gpu_scan(scan, values, count, size);
        const auto mismatch = std::mismatch(result.values.begin(), result.values.end(), expected.begin());
        EXPECT_TRUE(mismatch.first == result.values.end())
            << "size " << size << ", count " << count << ": first difference at "
            << (mismatch.first - result.values.begin());
        EXPECT_EQ(result.totals, (std::vector<std::uint32_t>{0xdeadbeefu, 0xdeadbeefu, total, 0xdeadbeefu}))
            << "size " << size << ", count " << count;
    }
};

TEST_F(GpuScanTest, ScanMatchesCpuAcrossBlockBoundaries) {
    constexpr std::uint32_t block = SCAN_BLOCK_SIZE;
    for (const std::uint32_t size : {0u, 1u, 2u, 1023u, 1024u, 1025u, block - 1, block, block + 1, 300000u})
        expect_scanned(size, size);
}

TEST_F(GpuScanTest, ScanOfSixteenMillionNeedsThreeLevelsAndMatches) {
    // More than SCAN_BLOCK_SIZE^2 elements: block sums of block sums (16M + 1 with 4096-blocks).
    constexpr std::uint32_t size = SCAN_BLOCK_SIZE * SCAN_BLOCK_SIZE + 1;
    expect_scanned(size, size, 3);
}

TEST_F(GpuScanTest, ScanUsesTheGpuCountAndLeavesTheRestUntouched) {
    expect_scanned(5000, 4097);
    expect_scanned(5000, 0);
    expect_scanned(3000, 1u << 30);  // clamped to the capacity
}

TEST_F(GpuScanTest, ScanWrapsLikeUint) {
    expect_scanned(4096, 4096, 0xffffffffu);
}

TEST_F(GpuScanTest, ScanRejectsInconsistentJobs) {
    Buffer values = make_buffer(std::vector<std::uint32_t>(64), "test scan values");
    const Buffer count = make_buffer(std::vector<std::uint32_t>{64u}, "test scan count");
    Buffer total = make_buffer(std::vector<std::uint32_t>(1), "test scan total");
    const auto job = [&](std::uint32_t max_count, std::size_t total_offset) {
        scan.record({.values = values,
                     .count_buffer = count,
                     .max_count = max_count,
                     .total_buffer = total,
                     .total_offset = total_offset});
    };
    EXPECT_THROW(job(65, 0), engine::Error);
    EXPECT_THROW(job(64, 4), engine::Error);
    EXPECT_THROW(job(PrefixScan::max_scan_count() + 1, 0), engine::Error);
    EXPECT_NO_THROW(job(64, 0));
}

}  // namespace
