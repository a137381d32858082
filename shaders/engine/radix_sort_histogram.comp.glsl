// Radix sort, upsweep: how many keys of each digit every tile holds. Written digit-major
// ([digit * tile_count + tile]) so that one exclusive scan of the whole array gives each
// (tile, digit) its first output position, tiles in input order within a digit: that is what
// keeps the sort stable across workgroups.
#include "radix_sort_common.glsl"

layout(std430, binding = SORT_BINDING_HISTOGRAM) writeonly buffer SortHistogram { uint histogram[]; };

shared uint s_digit_counts[SORT_RADIX_SIZE];

void main() {
    const uint lid = gl_LocalInvocationID.x;
    for (uint d = lid; d < SORT_RADIX_SIZE; d += SORT_WORKGROUP_SIZE) s_digit_counts[d] = 0u;
    barrier();
    const uint count = sort_params.count;
    for (uint round = 0u; round < SORT_ELEMENTS_PER_THREAD; ++round) {
        const uint i = tile_element(round);
        // Counting is order-independent, so plain shared atomics are fine here.
        if (i < count) atomicAdd(s_digit_counts[word_digit(load_key_word(i, u_word))], 1u);
    }
    barrier();
    const uint tile_count = sort_params.tile_count;
    for (uint d = lid; d < SORT_RADIX_SIZE; d += SORT_WORKGROUP_SIZE)
        histogram[d * tile_count + gl_WorkGroupID.x] = s_digit_counts[d];
}
