// Buffer declarations shared by the splat frame passes (layouts in splat_lod_shared.h).
#include "splat_lod_shared.h"

layout(std140, binding = SPLAT_UNIFORM_FRAME) uniform FrameBlock { FrameUniforms frame; };
