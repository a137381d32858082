// Mesh pass contract shared by C++ and GLSL: attribute locations and light limits.
#ifndef ENGINE_MESH_SHARED_H
#define ENGINE_MESH_SHARED_H

#define MESH_ATTRIBUTE_POSITION 0
#define MESH_ATTRIBUTE_NORMAL 1
#define MESH_ATTRIBUTE_UV 2
#define MESH_MAX_DIRECTIONAL_LIGHTS 4
#define MESH_BASE_COLOR_TEXTURE_UNIT 0
// The late mesh pass (MESH_LATE): a copy of the view depth the passes before it left.
#define MESH_SURFACE_DEPTH_TEXTURE_UNIT 1

#endif
