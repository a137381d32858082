// Radix sort, final copy: after an odd number of passes the result is in the internal buffers;
// this brings elements [0, count) back to the caller's, leaving the rest untouched.
#include "radix_sort_common.glsl"

layout(std430, binding = SORT_BINDING_KEYS_OUT) writeonly buffer SortKeysOut { SORT_KEY_TYPE keys_out[]; };
layout(std430, binding = SORT_BINDING_VALUES_OUT) writeonly buffer SortValuesOut { uint values_out[]; };

void main() {
    const uint count = sort_params.count;
    for (uint round = 0u; round < SORT_ELEMENTS_PER_THREAD; ++round) {
        const uint i = tile_element(round);
        if (i < count) {
            store_key(keys_out, i, load_key(i));
            values_out[i] = load_value(i);
        }
    }
}
