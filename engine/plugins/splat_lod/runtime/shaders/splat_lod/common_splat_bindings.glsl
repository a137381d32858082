// Buffer declarations shared by the splat frame passes (layouts in splat_lod_shared.h).
#include "splat_lod_shared.h"

layout(std140, binding = SPLAT_UNIFORM_FRAME) uniform FrameBlock { FrameUniforms frame; };

// True when this run of the steps draws one strip of the frame's tile rows, not all of them
// (SplatPassSettings::frame_memory_limit).
bool drawn_in_strips() { return frame.strip_first_row > 0u || frame.strip_end_row < frame.tiles.y; }
