// Shared by the radix sort stages: the key/value buffers, the GPU-written parameters and the
// digit of a key for the current pass. Keys are uvec2: x = low word (view depth as float bits),
// y = high word (tile index); the order is by (y, x).
#include "splat_lod_shared.h"

layout(local_size_x = SORT_WORKGROUP_SIZE) in;

layout(std430, binding = SORT_BINDING_KEYS_IN) readonly buffer SortKeysIn { uvec2 keys_in[]; };
// The same keys as words (2 * i + word), so a pass that only needs the digit loads one word.
layout(std430, binding = SORT_BINDING_KEYS_IN) readonly buffer SortKeyWordsIn { uint key_words_in[]; };
layout(std430, binding = SORT_BINDING_VALUES_IN) readonly buffer SortValuesIn { uint values_in[]; };
layout(std430, binding = SORT_BINDING_PARAMS) readonly buffer SortParamsBlock { SortParams sort_params; };

uniform uint u_word;        // 0: the digit is in the low word, 1: in the high word
uniform uint u_shift;       // first bit of the digit within that word
uniform uint u_digit_bits;  // bits of this pass's digit (the last pass may take fewer)

uint word_digit(uint word) { return bitfieldExtract(word, int(u_shift), int(u_digit_bits)); }
uint key_digit(uvec2 key) { return word_digit(u_word == 0u ? key.x : key.y); }

// The index of round `round`'s element for this invocation: a tile is SORT_ELEMENTS_PER_THREAD
// rounds of SORT_WORKGROUP_SIZE consecutive elements, so rounds and lanes both follow input order.
uint tile_element(uint round) {
    return gl_WorkGroupID.x * SORT_TILE_SIZE + round * SORT_WORKGROUP_SIZE + gl_LocalInvocationID.x;
}
