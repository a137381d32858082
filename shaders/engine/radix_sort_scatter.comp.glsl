// Radix sort, stable scatter. Each element goes to its (tile, digit) start from the scanned
// histogram plus its rank among the tile's earlier elements of the same digit. Ranks must follow
// input order, so instead of atomics (whose order is arbitrary) a round of SORT_WORKGROUP_SIZE
// elements sets one bit per lane in its digit's lane mask; an element's rank within the round is
// the number of set bits below its lane, and rounds are handled in order. No subgroup ops needed.
#include "radix_sort_common.glsl"

layout(std430, binding = SORT_BINDING_KEYS_OUT) writeonly buffer SortKeysOut { SORT_KEY_TYPE keys_out[]; };
layout(std430, binding = SORT_BINDING_VALUES_OUT) writeonly buffer SortValuesOut { uint values_out[]; };
layout(std430, binding = SORT_BINDING_HISTOGRAM) readonly buffer SortHistogram { uint digit_offsets[]; };

#define MASKS_PER_ROUND (SORT_RADIX_SIZE * SORT_MASK_WORDS)

// Next output position of each digit for this tile.
shared uint s_digit_next[SORT_RADIX_SIZE];
// Lane masks of two rounds: a round's masks are cleared while the next round fills the others,
// which saves a barrier per round.
shared uint s_lane_masks[2 * MASKS_PER_ROUND];

void clear_and_load_offsets() {
    const uint lid = gl_LocalInvocationID.x;
    const uint tile_count = sort_params.tile_count;
    for (uint d = lid; d < SORT_RADIX_SIZE; d += SORT_WORKGROUP_SIZE)
        s_digit_next[d] = digit_offsets[d * tile_count + gl_WorkGroupID.x];
    for (uint w = lid; w < 2u * MASKS_PER_ROUND; w += SORT_WORKGROUP_SIZE) s_lane_masks[w] = 0u;
}

// Lanes below this one with the same digit (rank) and all lanes with it (total). Branch-free:
// on CPU drivers (llvmpipe) divergent branches cost both sides.
uint rank_in_round(uint masks, out uint total) {
    const uint lid = gl_LocalInvocationID.x;
    const uint own_word = lid / 32u;
    const uint lower_lanes = (1u << (lid % 32u)) - 1u;
    uint rank = 0u;
    total = 0u;
    for (uint w = 0u; w < SORT_MASK_WORDS; ++w) {
        const uint lanes = s_lane_masks[masks + w];
        total += uint(bitCount(lanes));
        rank += uint(bitCount(w < own_word ? lanes : (w == own_word ? lanes & lower_lanes : 0u)));
    }
    return rank;
}

void main() {
    clear_and_load_offsets();
    barrier();
    const uint count = sort_params.count;
    const uint lane_bit = 1u << (gl_LocalInvocationID.x % 32u);
    const uint lane_word = gl_LocalInvocationID.x / 32u;
    for (uint round = 0u; round < SORT_ELEMENTS_PER_THREAD; ++round) {
        // The same for the whole workgroup, so leaving here keeps barriers in uniform control flow.
        if (tile_element(round) - gl_LocalInvocationID.x >= count) break;
        const uint i = tile_element(round);
        const bool valid = i < count;
        const uvec2 key = valid ? load_key(i) : uvec2(0u);
        const uint digit = key_digit(key);
        const uint masks = (round & 1u) * MASKS_PER_ROUND + digit * SORT_MASK_WORDS;
        if (valid) atomicOr(s_lane_masks[masks + lane_word], lane_bit);
        barrier();
        uint total = 0u;
        const uint rank = rank_in_round(masks, total);
        const uint destination = s_digit_next[digit] + rank;
        if (valid) {
            store_key(keys_out, destination, key);
            values_out[destination] = load_value(i);
        }
        barrier();
        // The digit's last lane in this round moves the digit's position past the round and
        // clears its masks for round + 2 (the other buffer is in use by round + 1).
        if (valid && rank + 1u == total) {
            s_digit_next[digit] = destination + 1u;
            for (uint w = 0u; w < SORT_MASK_WORDS; ++w) s_lane_masks[masks + w] = 0u;
        }
    }
}
