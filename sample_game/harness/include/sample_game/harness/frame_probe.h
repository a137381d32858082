#pragma once
// Draws one frame of the game's world and measures it into a FrameRecord: the frame's wall time
// (render() to glFinish(), so that the GPU work is inside it: on llvmpipe the GPU is the CPU),
// the GPU timer spans of the mesh and splat passes and the splat steps, the splat statistics
// (Gaussians drawn per level), the GPU scene's pages and uploads, and the streamer's counts.
// Waits for the GPU after every frame: a profile wants each frame's own numbers, not a pipeline.
#include "engine/render/render_target.h"
#include "sample_game/game_world.h"
#include "sample_game/harness/frame_record.h"

namespace sample_game {

// A frame whose key buffer overflowed (it needed more tile-splat pairs than the buffer held; the
// buffer grows after such a frame) drew fewer splats than it should: it is drawn again, up to
// this many times, and the complete draw is the one timed. The GPU upload is the first draw's.
inline constexpr int kMaxRedraws = 8;

// Draws `camera` into `target` (same size) and fills the record's timing, statistics, memory and
// streaming fields (not its pose fields: record_pose() does those).
void draw_and_measure(GameWorld& world, engine::Engine& engine, const engine::CameraView& camera,
                      engine::RenderTarget& target, FrameRecord& record);

// With a stereo pair this far apart (ProfileOptions::stereo_ipd): draws `camera`'s two eyes, timed to the
// GPU's finish, and each eye again with its own selection, and fills stereo_frame_ms and
// stereo_eye_psnr. Draws into `target`, which then holds the right eye with its own selection.
void measure_stereo(GameWorld& world, engine::Engine& engine, const engine::CameraView& camera, float ipd,
                    engine::RenderTarget& target, FrameRecord& record);

// The switch pop of a pair (splat_lod::eval::selection_switch_pop): draws `camera` again with the
// selection of `previous` (its view as CameraView::selection_view) into `target` and compares it with
// `image`, the frame as drawn; fills switch_pop.
void measure_switch_pop(GameWorld& world, engine::Engine& engine, const engine::CameraView& camera,
                        const engine::CameraView& previous, const engine::Image& image, engine::RenderTarget& target,
                        FrameRecord& record);

// The record's pose fields: segment, path parameter, eye, height above the ground and distance from
// the world's centre.
void record_pose(const GameWorld& world, const PathPose& pose, FrameRecord& record);

// The streamer's side of the record: resident and uploaded bytes, chunk census, failures.
void record_streaming(GameWorld& world, FrameRecord& record);

}  // namespace sample_game
