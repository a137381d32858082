// A splat's opacity at a pixel (docs/algorithms.md §1): α = min(0.99, o·exp(−½ dᵀQd)), d the pixel
// centre minus the splat's mean, Q its conic; the raster and picking both call it, so that they agree.
float splat_alpha(vec2 d, vec4 conic, float opacity) {
    float power = -0.5 * (conic.x * d.x * d.x + 2.0 * conic.y * d.x * d.y + conic.z * d.y * d.y);
    return min(0.99, opacity * exp(power));
}
