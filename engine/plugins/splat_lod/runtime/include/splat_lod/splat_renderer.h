#pragma once
// The runtime's public face for tools, games and tests: the splat pass that the plugin adds to an
// engine's renderer, seen through a small handle. Its settings, the statistics of the latest frame
// it read back, the GPU memory of its scene (pages of Gaussians), reserving that memory up front,
// the low-resolution image of the upscaler and the splats' depth (for tests that check them against the
// CPU reference).
// The pass itself stays private to the plugin.
#include <cstdint>
#include <optional>

#include <glm/glm.hpp>
#include <vector>

#include "engine/render/picking.h"
#include "splat_lod/msgs/lod_settings.h"
#include "splat_lod/msgs/splat_statistics.h"

#include "splat_lod/core/lod_selection.h"
#include "splat_lod/core/upscale.h"
#include "splat_lod/gpu_storage.h"
#include "splat_lod/splat_lod_shared.h"

namespace engine {
class MessageBus;
class Renderer;
}  // namespace engine

namespace splat_lod {

class SplatPass;

// How the tile raster reads the splats it blends (docs/algorithms.md §1, "Raster"); with texel the
// project, bin, sort and tile-range passes also read their inputs through buffer textures, else
// storage buffers.
enum class RasterFetch {
    automatic,  // texel on CPU drivers (Mesa llvmpipe, softpipe), shared elsewhere
    texel,      // every pixel fetches each splat through buffer textures
    shared,     // the tile stages batches of splats in shared memory, one read per splat and tile
};
const char* to_string(RasterFetch fetch);

// The pass's own technical settings, for measurements and tests. What a user chooses (the selection
// rule, the render scale and its upscaler, the mip filter, the level colouring and the splat budget) is
// plugin_msgs::LodSettings, which reaches the pass one way only: published on the engine's bus, where
// the pass takes each message whole (SplatRenderer::lod() reads it back).
//   With render_scale < 1 the splats are rasterised at that fraction of the output size with their
// analytic image derivatives and brought to the output by the upscaler (docs/algorithms.md §5). A
// splat budget, when the selection would draw more, makes the frame select as if every coverage were
// β times smaller (S_T and the coverage ranges β times larger: coarser levels), the smallest β in
// eighth-octave steps that fits, chosen on the GPU in the same frame; if even β ≈ 3700 does not fit,
// the smallest of those Gaussians are dropped. Invalid settings of either kind make the frame throw
// engine::Error.
struct SplatPassSettings {
    float znear = 0.2f;     // docs/algorithms.md §1
    float dilation = 0.3f;  // the EWA low-pass, in px²
    // Skip whole project workgroups whose Gaussians are all too small to be selected (exact: the
    // image and counts are the same either way; off only to measure what it saves).
    bool cluster_skipping = true;
    // Drop whole clusters that the view frustum leaves out before per-Gaussian work (exact, like the
    // skipping; off only to measure what it saves and to test that the image does not change).
    bool frustum_culling = true;
    // Resolution-consistent dilation: at render scale s the EWA low-pass is dilation·s² low-res px²,
    // the same blur as the native render (off only to measure the plain 0.3 px²).
    bool scaled_dilation = true;
    // Raster tile side in pixels (4, 8 or 16). The cost balances per-pixel list length (the splats
    // touching the tile) against tile-splat pairs to sort; why 16 natively and 8 below render scale 1
    // is measured in docs/benchmarks.md ("Tile size").
    std::uint32_t tile_size = SPLAT_TILE_SIZE;
    std::uint32_t low_res_tile_size = 8;  // raster tile side below render scale 1 (8 or 16)
    // Bin each splat into the tiles its α ≥ 1/255 ellipse touches rather than every tile of its bounding
    // box (docs/algorithms.md §1, "Tile footprint"): fewer tile-splat pairs, the same image; off only to
    // measure what it saves.
    bool exact_tiles = true;
    // One-word sort keys, (tile, depth quantised to the frame's depth range), whenever the tile index
    // leaves at least 16 bits for depth: 4 radix passes instead of 6 or 7 (docs/algorithms.md §1,
    // "Sort keys"); off only to measure what it saves.
    bool compact_sort_keys = true;
    RasterFetch raster_fetch = RasterFetch::automatic;
    // How the scene's Gaussians are stored on the GPU (docs/gpu_storage.md): compact, 20 bytes a
    // Gaussian plus 8 or 16 bytes of higher SH bands, or full floats where every trained bit must
    // reach the screen. A change re-uploads the scene.
    GpuStorage gpu_storage = GpuStorage::compact;
    // Keep the splats' own depths of each frame, the median and the expected depth (SplatDepth), in an
    // image at the output size that read_splat_depth() returns: 8 bytes a pixel. The target's view depth
    // gets the median depth merged with the meshes' either way (docs/algorithms.md §1, "Depth").
    bool splat_depth = false;
    // The most bytes the buffers that follow the view may take (the projected splats, the sort keys with
    // the sort's own copy); 0: no limit. A view that needs more is drawn in strips of tile rows, each
    // running the steps from the selection to the raster over the splats that touch its rows, with the
    // same pixels (docs/gpu_storage.md, "Strips"). Under a splat budget a frame is one strip: the budget
    // chooses over the whole view, and it bounds the splats already.
    std::uint64_t frame_memory_limit = 0;
};

// The splats' view depths z = −z_view of a frame, per output pixel, rows top first, +inf where there is
// none (docs/algorithms.md §1, "Depth"): `median`, the depth of the splat with which the accumulated
// opacity first exceeds ½ (what the target's view depth gets, merged with the meshes'), and `expected`,
// Σ dᵢαᵢTᵢ / A over the splats blended. Splats behind a mesh are not blended and count for neither.
// Below render scale 1 each output pixel has the depths of the nearest low-resolution texel around it
// that has them, the median where the upscaled opacity reaches ½ (docs/algorithms.md §1, "Depth").
struct SplatDepth {
    int width = 0, height = 0;
    std::vector<float> median, expected;
};

// The GPU memory of the pass's scene: Gaussians live in fixed-size pages (docs/world_lod.md).
struct SplatMemory {
    std::uint64_t live_gaussians = 0;  // Gaussians of the components now resident
    std::uint32_t gaussian_count = 0;  // slots in use by the resident instances
    std::uint32_t pages_in_use = 0;
    std::uint32_t free_pages = 0;
    std::uint64_t page_bytes = 0;         // bytes of one page (Gaussians, SH, cluster records)
    std::uint64_t last_upload_bytes = 0;  // bytes the latest frame uploaded
    std::uint32_t sh_stride = 0;          // SH stored per Gaussian: floats (full) or 32-bit words (compact)
    // What the splat pass holds on the GPU: the scene's buffers (their capacity, pages in use or not),
    // and the per-frame buffers sized by what the latest frames drew (the projected splats, the
    // key_capacity() sort keys with the sort's own copy, per-cluster counts, tile ranges) with the
    // low-resolution images.
    std::uint64_t scene_bytes = 0;
    std::uint64_t frame_bytes = 0;
    // Of frame_bytes, those SplatPassSettings::frame_memory_limit bounds: the projected splats, the keys
    // and the sort's own buffers.
    std::uint64_t view_bytes = 0;
    // How often the latest frame ran its selection (steps 1–2): 2 when it projected more splats than
    // the buffer sized by the frame before held, which then grew.
    std::uint32_t selection_runs = 0;
    // Strips the latest frame was drawn in (SplatPassSettings::frame_memory_limit): 1 without a limit.
    std::uint32_t strips = 1;
    GpuStorage storage = GpuStorage::compact;  // how the scene is stored (docs/gpu_storage.md)
};

// A non-owning handle to the plugin's splat pass in `renderer`; valid while the engine runs.
class SplatRenderer {
public:
    // Throws engine::Error when the splat_lod plugin is not started in this renderer.
    explicit SplatRenderer(engine::Renderer& renderer);

    SplatPassSettings& settings();
    const SplatPassSettings& settings() const;
    // The LOD settings the pass draws with: the last plugin_msgs::LodSettings published on the engine's
    // bus (the defaults before any). To change them, publish a new one.
    const plugin_msgs::LodSettings& lod() const;

    // The statistics of the latest frame read back (a frame or more late; none before the first).
    const std::optional<plugin_msgs::SplatStatistics>& latest_statistics() const;
    // Waits for the GPU and reads back every frame rendered so far, publishing their statistics.
    void wait_for_statistics(engine::MessageBus& bus);
    // Tile-splat pairs the key buffer holds now: what the latest frame needed and a little room.
    std::uint32_t key_capacity() const;
    // The raster fetch the latest frame used (settings().raster_fetch resolved for this driver).
    RasterFetch raster_fetch_in_use() const;

    SplatMemory memory() const;
    // Allocates pages for `gaussians` Gaussians of SH degree `sh_degree` up front, so that streaming
    // within that budget never grows a buffer mid-walk.
    void reserve(std::uint64_t gaussians, int sh_degree);  // stored as settings().gpu_storage says

    // The low-resolution image of the latest frame rendered below render scale 1: colour, its
    // analytic gradients and the front depth (tests and evaluation; waits for the GPU).
    upscale::GradientImage read_low_res_image() const;
    std::vector<float> read_low_res_front_depth() const;
    // The splats' depths of the latest frame drawn with settings().splat_depth (waits for the GPU);
    // empty before one.
    SplatDepth read_splat_depth() const;

    // Picking the splats alone (docs/picking.md; engine::Renderer::pick picks meshes too): asks what the
    // next frame's splats put under `pixel` (image space, top-left origin), the point on the pixel's ray
    // where their accumulated opacity first passes ½ before any mesh, with the component and node of the
    // splat that makes it pass. pick_result() is not ready until the GPU has answered, a frame or more
    // after the pixel was drawn, and never waits for it; with `wait` it reads the answer back now
    // (blocking, for tools; throws engine::Error when no frame has drawn the pixel yet).
    std::uint64_t pick(glm::ivec2 pixel);
    engine::PickResult pick_result(std::uint64_t ticket, bool wait = false) const;
    // Pick readbacks still in flight (never more than four).
    std::size_t picks_in_flight() const;

private:
    engine::Renderer* renderer_;
    SplatPass* pass_;
};

}  // namespace splat_lod
