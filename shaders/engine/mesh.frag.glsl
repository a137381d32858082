#include "mesh_shared.h"
#include "../common/color_space.glsl"

in vec3 v_normal;
in vec2 v_uv;
in float v_view_depth;

uniform vec4 u_base_color_factor;        // linear
uniform bool u_has_base_color_texture;   // texture is sRGB, sampled as linear
layout(binding = MESH_BASE_COLOR_TEXTURE_UNIT) uniform sampler2D u_base_color_texture;
uniform vec3 u_ambient;                  // linear radiance
uniform int u_light_count;
uniform vec3 u_light_direction[MESH_MAX_DIRECTIONAL_LIGHTS];  // world, pointing from the light
uniform vec3 u_light_color[MESH_MAX_DIRECTIONAL_LIGHTS];      // linear, intensity applied

#ifdef MESH_LATE
// Drawn after the plugin passes: behind a surface they left in the view depth, a fragment is hidden.
layout(binding = MESH_SURFACE_DEPTH_TEXTURE_UNIT) uniform sampler2D u_surface_depth;
#endif

layout(location = 0) out vec4 out_color;       // display space (sRGB-encoded)
layout(location = 1) out float out_view_depth; // z = -z_view, read by splat passes

void main() {
#ifdef MESH_LATE
    if (!(v_view_depth < texelFetch(u_surface_depth, ivec2(gl_FragCoord.xy), 0).r)) discard;
#endif
    vec4 base = u_base_color_factor;
    if (u_has_base_color_texture) base *= texture(u_base_color_texture, v_uv);
    vec3 n = normalize(v_normal);
    if (!gl_FrontFacing) n = -n;  // double-sided surfaces light their back like their front
    vec3 radiance = u_ambient;
    for (int i = 0; i < u_light_count; ++i)
        radiance += u_light_color[i] * max(dot(n, -u_light_direction[i]), 0.0);
    out_color = vec4(linear_to_srgb(base.rgb * radiance), 1.0);
    out_view_depth = v_view_depth;
}
