// How the project and trim passes read the scene's Gaussians (GpuStorage, splat_lod_shared.h):
//   GpuGaussian load_gaussian(uint index)   position, activated opacity, 3D covariance, instance, LOD
//   vec4 load_lod(uint index)                coverage_min, coverage_max, level (GpuGaussian::lod)
//   vec3 sh_coefficient(uint index, uint k)  SH coefficient k (0 is DC) of the three channels
// Full storage reads GpuGaussian records and float SH; compact storage (SPLAT_COMPACT_STORAGE) decodes
// 20-byte records and SH words against their page's GpuPageCodec, bit for bit as decode_compact in
// splat_lod/core/compact_gaussians.h does. With SPLAT_INPUT_TEXELS the same words are read through
// buffer textures (one gather on CPU drivers instead of a loop over the SIMD lanes).

#ifdef SPLAT_COMPACT_STORAGE
#ifdef SPLAT_INPUT_TEXELS
layout(binding = SPLAT_TEXTURE_GAUSSIANS) uniform usamplerBuffer gaussian_texels;  // r32ui, 5 per Gaussian
layout(binding = SPLAT_TEXTURE_SH) uniform usamplerBuffer sh_texels;              // r32ui
layout(binding = SPLAT_TEXTURE_PAGE_CODECS) uniform usamplerBuffer codec_texels;   // rgba32ui, 5 per page
uint record_word(uint index, uint w) { return texelFetch(gaussian_texels, int(index * SPLAT_COMPACT_WORDS + w)).r; }
uint sh_word(uint i) { return texelFetch(sh_texels, int(i)).r; }
vec4 codec_vec4(uint page, int k) { return uintBitsToFloat(texelFetch(codec_texels, int(page) * 5 + k)); }
#else
layout(std430, binding = SPLAT_BINDING_GAUSSIANS) readonly buffer Gaussians { uint gaussian_words[]; };
layout(std430, binding = SPLAT_BINDING_SH) readonly buffer ShWords { uint sh_words[]; };
layout(std430, binding = SPLAT_BINDING_PAGE_CODECS) readonly buffer PageCodecs { vec4 codec_words[]; };
uint record_word(uint index, uint w) { return gaussian_words[index * SPLAT_COMPACT_WORDS + w]; }
uint sh_word(uint i) { return sh_words[i]; }
vec4 codec_vec4(uint page, int k) { return codec_words[page * 5u + uint(k)]; }
#endif
// GpuPageCodec's members by position.
#define CODEC_POSITION_LO 0
#define CODEC_POSITION_STEP 1
#define CODEC_COLOUR_LO 2
#define CODEC_COLOUR_STEP 3
#define CODEC_SH_MAX 4

// compact_sh_band(): per stored degree and band, the levels L, the first bit and the bits per
// coefficient (0: trits, the first 20 the base-3 digits of word 3, the 21st at bits 93–94).
uvec3 sh_band_code(uint degree, uint band) {
    uint exponents = 4u * degree;
    if (degree == 1u) return uvec3(31u, exponents, 6u);
    if (degree == 2u) return band == 1u ? uvec3(31u, exponents, 6u) : uvec3(7u, exponents + 54u, 4u);
    if (band == 1u) return uvec3(7u, exponents, 4u);
    if (band == 2u) return uvec3(3u, exponents + 36u, 3u);
    return uvec3(1u, 0u, 0u);
}
// 2^(−e/2), the same literals as compact_sh.cpp.
const float SH_HALF_OCTAVES[16] = float[](1.0, 0.70710678118654752, 0.5, 0.35355339059327376, 0.25, 0.17677669529663688,
                                          0.125, 0.08838834764831844, 0.0625, 0.04419417382415922, 0.03125,
                                          0.02209708691207961, 0.015625, 0.011048543456039805, 0.0078125,
                                          0.0055242717280199025);
const uint SH_POWERS_OF_3[20] = uint[](1u, 3u, 9u, 27u, 81u, 243u, 729u, 2187u, 6561u, 19683u, 59049u, 177147u,
                                       531441u, 1594323u, 4782969u, 14348907u, 43046721u, 129140163u, 387420489u,
                                       1162261467u);

uint page_of(uint index) { return index / uint(SPLAT_PROJECT_WORKGROUP_SIZE); }

// Coverage bound codes: 0 unset (−1), 1 zero, else 2^(lo + (q − 2)·step).
float decode_coverage(uint code, float lo, float step) {
    if (code == 0u) return -1.0;
    if (code == 1u) return 0.0;
    return exp2(lo + float(code - 2u) * step);
}

vec4 load_lod(uint index) {
    uint w4 = record_word(index, 4u);
    vec4 lo = codec_vec4(page_of(index), CODEC_COLOUR_LO), step = codec_vec4(page_of(index), CODEC_COLOUR_STEP);
    return vec4(decode_coverage(bitfieldExtract(w4, 10, 11), lo.w, step.w),
                decode_coverage(bitfieldExtract(w4, 21, 11), lo.w, step.w), float(bitfieldExtract(w4, 8, 2) + 1u), 0.0);
}

// The smallest-three rotation code as a rotation matrix (columns), the quaternion (w, x, y, z) unit length.
mat3 decode_rotation(uint code) {
    const float half_sqrt2 = 0.70710678118654752;
    uint largest = code >> 30;
    vec4 q;
    float sum = 0.0;
    uint slot = 0u;
    for (uint k = 0u; k < 4u; ++k) {
        if (k == largest) continue;
        q[k] = (float(bitfieldExtract(code, int(10u * slot), 10)) * (2.0 / 1023.0) - 1.0) * half_sqrt2;
        sum += q[k] * q[k];
        ++slot;
    }
    q[largest] = sqrt(max(0.0, 1.0 - sum));
    float w = q.x, x = q.y, y = q.z, z = q.w;
    return mat3(1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + w * z), 2.0 * (x * z - w * y),
                2.0 * (x * y - w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z + w * x),
                2.0 * (x * z + w * y), 2.0 * (y * z - w * x), 1.0 - 2.0 * (x * x + y * y));
}

GpuGaussian load_gaussian(uint index) {
    uint page = page_of(index);
    uint w0 = record_word(index, 0u), w1 = record_word(index, 1u), w2 = record_word(index, 2u);
    uint w3 = record_word(index, 3u);
    vec4 lo = codec_vec4(page, CODEC_POSITION_LO), step = codec_vec4(page, CODEC_POSITION_STEP);
    vec3 q = vec3(bitfieldExtract(w0, 0, 16), bitfieldExtract(w0, 16, 16), bitfieldExtract(w1, 0, 16));
    vec3 position = lo.xyz + q * step.xyz;
    vec3 log_scale = lo.w + vec3(bitfieldExtract(w1, 24, 8), bitfieldExtract(w3, 0, 8), bitfieldExtract(w3, 8, 8)) * step.w;
    mat3 m = decode_rotation(w2);
    vec3 s = exp(log_scale);
    m[0] *= s.x;
    m[1] *= s.y;
    m[2] *= s.z;
    mat3 sigma = m * transpose(m);
    float opacity = float(bitfieldExtract(w1, 16, 8)) / 255.0;
    float instance = codec_vec4(page, CODEC_SH_MAX).w;
    return GpuGaussian(vec4(position, opacity), vec4(sigma[0][0], sigma[0][1], sigma[0][2], sigma[1][1]),
                       vec4(sigma[1][2], sigma[2][2], 0.0, instance), load_lod(index));
}

vec3 sh_coefficient(uint index, uint k) {
    uint page = page_of(index);
    if (k == 0u) {
        uvec3 c = uvec3(bitfieldExtract(record_word(index, 3u), 16, 8), bitfieldExtract(record_word(index, 3u), 24, 8),
                        bitfieldExtract(record_word(index, 4u), 0, 8));
        vec3 colour = codec_vec4(page, CODEC_COLOUR_LO).xyz + vec3(c) * codec_vec4(page, CODEC_COLOUR_STEP).xyz;
        return (colour - 0.5) / 0.28209479177387814;  // the DC basis value, SH_C0
    }
    // The higher bands as compact_sh_band() lays them out for the stored degree: q·M·2^(−e/2)/L.
    uint band = k < 4u ? 1u : (k < 9u ? 2u : 3u), degree = frame.sh_storage_degree;
    uint base = index * frame.sh_stride;
    uint e = bitfieldExtract(sh_word(base), int(4u * (band - 1u)), 4);
    float s = codec_vec4(page, CODEC_SH_MAX)[band - 1u] * SH_HALF_OCTAVES[e];
    uvec3 code = sh_band_code(degree, band);  // levels, first bit, bits (0: trits)
    uint j0 = (k - band * band) * 3u;
    vec3 v;
    for (uint c = 0u; c < 3u; ++c) {
        uint j = j0 + c;
        int q;
        if (code.z == 0u) {
            uint t = j < 20u ? (sh_word(base + 3u) / SH_POWERS_OF_3[j]) % 3u : bitfieldExtract(sh_word(base + 2u), 29, 2);
            q = t == 1u ? 1 : (t == 2u ? -1 : 0);
        } else {
            uint bit = code.y + j * code.z, word = bit / 32u, shift = bit % 32u;
            uint field = sh_word(base + word) >> shift;
            if (shift + code.z > 32u) field |= sh_word(base + word + 1u) << (32u - shift);
            q = bitfieldExtract(int(field), 0, int(code.z));  // sign-extended
        }
        v[c] = s * (float(q) / float(code.x));
    }
    return v;
}

#else  // full storage
#ifdef SPLAT_INPUT_TEXELS
layout(binding = SPLAT_TEXTURE_GAUSSIANS) uniform usamplerBuffer gaussian_texels;  // rgba32ui, 4 per Gaussian
layout(binding = SPLAT_TEXTURE_SH) uniform usamplerBuffer sh_texels;              // rgb32ui, 1 per coefficient
vec4 fetch_vec4(usamplerBuffer t, int i) { return uintBitsToFloat(texelFetch(t, i)); }
GpuGaussian load_gaussian(uint index) {
    int b = int(index) * 4;
    return GpuGaussian(fetch_vec4(gaussian_texels, b), fetch_vec4(gaussian_texels, b + 1),
                       fetch_vec4(gaussian_texels, b + 2), fetch_vec4(gaussian_texels, b + 3));
}
vec3 sh_coefficient(uint index, uint k) {
    return uintBitsToFloat(texelFetch(sh_texels, int(index * frame.sh_stride / 3u + k)).rgb);
}
#else
layout(std430, binding = SPLAT_BINDING_GAUSSIANS) readonly buffer Gaussians { GpuGaussian gaussians[]; };
layout(std430, binding = SPLAT_BINDING_SH) readonly buffer ShCoefficients { float sh[]; };
GpuGaussian load_gaussian(uint index) { return gaussians[index]; }
vec3 sh_coefficient(uint index, uint k) {
    uint base = index * frame.sh_stride + k * 3u;
    return vec3(sh[base], sh[base + 1u], sh[base + 2u]);
}
#endif
vec4 load_lod(uint index) { return load_gaussian(index).lod; }
#endif
