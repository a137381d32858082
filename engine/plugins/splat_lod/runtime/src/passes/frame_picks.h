#pragma once
// Picking in the splat frame (engine/render/picking.h, docs/picking.md): the pixels a frame is asked
// about go to the GPU with the frame (SplatPicks), splat_pick.comp.glsl answers them after the sort,
// and the answers are copied into one of four readback buffers behind a fence, read when the GPU is done
// (never stalling a frame unless all four are in flight or a blocking answer is asked for) and kept by
// ticket with the world point and the component they name.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/gl/objects.h"
#include "engine/render/camera.h"
#include "engine/render/picking.h"

namespace splat_lod {

struct SplatComponent;

class FramePicks {
public:
    // The frame's requests, their raster pixels (render scale `scale`, raster `raster_size`) in
    // `picks` (gpu::SplatPicks); false when there are none and nothing was written.
    bool upload(std::span<const engine::PickRequest> requests, float scale, glm::ivec2 raster_size,
                engine::gl::Buffer& picks);
    // After splat_pick ran: copies its answers for reading back, with what turns them into hits (the
    // frame's camera and the component of each instance index).
    void record(const engine::gl::Buffer& picks, const engine::CameraView& camera,
                std::vector<const SplatComponent*> components);
    // The answer for `ticket`: ready once its frame is read back (`wait`: reads it back now, blocking).
    engine::PickResult answer(std::uint64_t ticket, bool wait);
    // Readbacks of answers not read yet (a test's count of what is in flight).
    std::size_t in_flight() const;

private:
    struct Readback {
        engine::gl::Buffer buffer{engine::gl::NoCreate};
        engine::gl::Fence fence;
        std::vector<engine::PickRequest> requests;
        engine::CameraView camera;
        std::vector<const SplatComponent*> components;  // by instance index
    };
    void collect(Readback& r);

    std::vector<engine::PickRequest> requests_;  // of the frame being drawn
    std::array<Readback, 4> readbacks_;
    std::uint64_t frames_ = 0;
    engine::PickAnswers answers_;
};

}  // namespace splat_lod
