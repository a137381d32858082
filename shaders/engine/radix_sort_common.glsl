// Shared by the radix sort stages: the key/value buffers, the GPU-written parameters and the
// digit of a key for the current pass. Keys are uvec2: x = low word (view depth as float bits),
// y = high word (tile index); the order is by (y, x).
#include "gpu_sort_shared.h"

layout(local_size_x = SORT_WORKGROUP_SIZE) in;

layout(std430, binding = SORT_BINDING_KEYS_IN) readonly buffer SortKeysIn { uvec2 keys_in[]; };
// The same keys as words (2 * i + word), so a pass that only needs the digit loads one word.
layout(std430, binding = SORT_BINDING_KEYS_IN) readonly buffer SortKeyWordsIn { uint key_words_in[]; };
layout(std430, binding = SORT_BINDING_VALUES_IN) readonly buffer SortValuesIn { uint values_in[]; };
#ifdef SORT_TEXEL_READS
// The same input through buffer textures (SortJob::texel_reads: on CPU drivers a texel fetch is one
// gather where a storage load is a loop over the SIMD lanes).
layout(binding = SORT_TEXTURE_KEYS_IN) uniform usamplerBuffer key_texels_in;      // rg32ui
layout(binding = SORT_TEXTURE_VALUES_IN) uniform usamplerBuffer value_texels_in;  // r32ui
uvec2 load_key(uint i) { return texelFetch(key_texels_in, int(i)).xy; }
uint load_key_word(uint i, uint word) { return texelFetch(key_texels_in, int(i))[word]; }
uint load_value(uint i) { return texelFetch(value_texels_in, int(i)).x; }
#else
uvec2 load_key(uint i) { return keys_in[i]; }
uint load_key_word(uint i, uint word) { return key_words_in[2u * i + word]; }
uint load_value(uint i) { return values_in[i]; }
#endif
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
