// Distance fog (engine/render/fog_pass.h): one invocation per pixel. A pixel with a finite view depth z
// moves toward the fog colour by f = 1 − exp(−density · max(z − start, 0)), mixed in linear light;
// where nothing is (+inf) the background stays as it is.
#include "../common/color_space.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba8) uniform coherent image2D u_color;  // display space (sRGB-encoded values)
layout(binding = 1) uniform sampler2D u_view_depth;            // z = −z_view, +inf where nothing is

uniform vec3 u_fog;        // the fog colour, display space
uniform float u_density;    // per metre
uniform float u_start;      // metres before the fog begins

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(u_color)))) return;
    float z = texelFetch(u_view_depth, pixel, 0).r;
    if (isinf(z) || isnan(z)) return;
    float f = 1.0 - exp(-u_density * max(z - u_start, 0.0));
    vec3 c = srgb_to_linear(imageLoad(u_color, pixel).rgb);
    imageStore(u_color, pixel, vec4(linear_to_srgb(mix(c, srgb_to_linear(u_fog), f)), 1.0));
}
