// Shared by the radix sort stages: the key/value buffers, the GPU-written parameters and the
// digit of a key for the current pass. Keys are uvec2: x = low word (view depth as float bits),
// y = high word (tile index); the order is by (y, x). One-word keys are the low word alone.
#include "gpu_sort_shared.h"

layout(local_size_x = SORT_WORKGROUP_SIZE) in;

// With SORT_ONE_WORD_KEYS (SortJob::key_words 1) a key is one uint, loaded as uvec2(word, 0) so that the
// stages are the same; the keys out are written back as one word (store_key).
#ifdef SORT_ONE_WORD_KEYS
#define SORT_KEY_WORDS 1u
#define SORT_KEY_TYPE uint
#define store_key(keys, i, key) keys[i] = (key).x
#else
#define SORT_KEY_WORDS 2u
#define SORT_KEY_TYPE uvec2
#define store_key(keys, i, key) keys[i] = (key)
#endif
layout(std430, binding = SORT_BINDING_KEYS_IN) readonly buffer SortKeysIn { SORT_KEY_TYPE keys_in[]; };
// The same keys as words (SORT_KEY_WORDS * i + word), so a pass that only needs the digit loads one word.
layout(std430, binding = SORT_BINDING_KEYS_IN) readonly buffer SortKeyWordsIn { uint key_words_in[]; };
layout(std430, binding = SORT_BINDING_VALUES_IN) readonly buffer SortValuesIn { uint values_in[]; };
#ifdef SORT_TEXEL_READS
// The same input through buffer textures (SortJob::texel_reads: on CPU drivers a texel fetch is one
// gather where a storage load is a loop over the SIMD lanes).
layout(binding = SORT_TEXTURE_KEYS_IN) uniform usamplerBuffer key_texels_in;      // rg32ui (r32ui: one word)
layout(binding = SORT_TEXTURE_VALUES_IN) uniform usamplerBuffer value_texels_in;  // r32ui
#ifdef SORT_ONE_WORD_KEYS
uvec2 load_key(uint i) { return uvec2(texelFetch(key_texels_in, int(i)).x, 0u); }
#else
uvec2 load_key(uint i) { return texelFetch(key_texels_in, int(i)).xy; }
#endif
uint load_key_word(uint i, uint word) { return texelFetch(key_texels_in, int(i))[word]; }
uint load_value(uint i) { return texelFetch(value_texels_in, int(i)).x; }
#else
#ifdef SORT_ONE_WORD_KEYS
uvec2 load_key(uint i) { return uvec2(keys_in[i], 0u); }
#else
uvec2 load_key(uint i) { return keys_in[i]; }
#endif
uint load_key_word(uint i, uint word) { return key_words_in[SORT_KEY_WORDS * i + word]; }
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
