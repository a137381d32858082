// Real spherical harmonics up to degree 3 (the 3DGS basis and constants), evaluated for a unit
// direction; coefficient k (0 is DC) of Gaussian `index` is read by sh_coefficient(index, k) of the
// scene's storage (common_splat_storage.glsl).
const float SH_C0 = 0.28209479177387814;
const float SH_C1 = 0.4886025119029199;
const float SH_C2[5] = float[](1.0925484305920792, -1.0925484305920792, 0.31539156525252005,
                               -1.0925484305920792, 0.5462742152960396);
const float SH_C3[7] = float[](-0.5900435899266435, 2.890611442640554, -0.4570457994644658, 0.3731763325901154,
                               -0.4570457994644658, 1.445305721320277, -0.5900435899266435);

// docs/algorithms.md §1: SH in the direction from the camera centre to the Gaussian, + 0.5, clamped at 0.
vec3 evaluate_sh(uint index, uint degree, vec3 d) {
    vec3 c = SH_C0 * sh_coefficient(index, 0u);
    if (degree >= 1u) {
        float x = d.x, y = d.y, z = d.z;
        c += -SH_C1 * y * sh_coefficient(index, 1u) + SH_C1 * z * sh_coefficient(index, 2u) - SH_C1 * x * sh_coefficient(index, 3u);
        if (degree >= 2u) {
            float xx = x * x, yy = y * y, zz = z * z, xy = x * y, yz = y * z, xz = x * z;
            c += SH_C2[0] * xy * sh_coefficient(index, 4u) + SH_C2[1] * yz * sh_coefficient(index, 5u) +
                 SH_C2[2] * (2.0 * zz - xx - yy) * sh_coefficient(index, 6u) + SH_C2[3] * xz * sh_coefficient(index, 7u) +
                 SH_C2[4] * (xx - yy) * sh_coefficient(index, 8u);
            if (degree >= 3u) {
                c += SH_C3[0] * y * (3.0 * xx - yy) * sh_coefficient(index, 9u) +
                     SH_C3[1] * xy * z * sh_coefficient(index, 10u) +
                     SH_C3[2] * y * (4.0 * zz - xx - yy) * sh_coefficient(index, 11u) +
                     SH_C3[3] * z * (2.0 * zz - 3.0 * xx - 3.0 * yy) * sh_coefficient(index, 12u) +
                     SH_C3[4] * x * (4.0 * zz - xx - yy) * sh_coefficient(index, 13u) +
                     SH_C3[5] * z * (xx - yy) * sh_coefficient(index, 14u) +
                     SH_C3[6] * x * (xx - 3.0 * yy) * sh_coefficient(index, 15u);
            }
        }
    }
    return max(c + 0.5, vec3(0.0));
}
