#include "mesh_shared.h"

layout(location = MESH_ATTRIBUTE_POSITION) in vec3 in_position;
layout(location = MESH_ATTRIBUTE_NORMAL) in vec3 in_normal;
layout(location = MESH_ATTRIBUTE_UV) in vec2 in_uv;

uniform mat4 u_model;
uniform mat4 u_view;
uniform mat4 u_projection;  // already flipped for the render target (row 0 on top)
uniform mat3 u_normal_matrix;

out vec3 v_normal;
out vec2 v_uv;
out float v_view_depth;

void main() {
    vec4 view_position = u_view * u_model * vec4(in_position, 1.0);
    v_normal = u_normal_matrix * in_normal;
    v_uv = in_uv;
    v_view_depth = -view_position.z;
    gl_Position = u_projection * view_position;
}
