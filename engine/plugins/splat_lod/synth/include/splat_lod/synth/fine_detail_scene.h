#pragma once
// Procedural Gaussian splat content with the fine, high-contrast detail that aliases when seen
// small: foliage, a picket fence, grass. It is the evaluation scene of the multi-scale LOD bake
// and the building blocks of generated outdoor worlds, so every builder appends to a caller's
// SplatCloud and takes a `detail` factor that thins the content out.
//
// Conventions: Y-up, metres, the stored 3DGS parameterisation (log-scales, opacity logits, SH DC
// = (rgb − 0.5) / kShC0, rotation (w, x, y, z) whose matrix columns are the Gaussian's local axes),
// SH degree 0 (a cloud of higher degree gets zero rest coefficients), LOD attributes left as
// SplatCloud::resize() sets them (level 1, unset coverage).
//
// Reproducibility: the same seed gives the same bytes on every platform. The generator uses its
// own RNG and distributions and its own sine, cosine and logarithm; beyond exact operations
// (floor, frexp) its only library arithmetic is +, −, ×, ÷ and sqrt, which IEEE 754 rounds
// exactly. Its sources switch off the fusing of a·b + c into one rounding (FMA), which GCC and
// Clang otherwise do on AArch64 and on x86-64 built for Haswell or later; -ffast-math or
// -ffp-contract=fast would override that. Nothing depends on thread count, time or hash-map order.
#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

#include "splat_lod/core/splat_cloud.h"

namespace splat_lod::synth {

// xoshiro256** seeded through splitmix64. `stream` selects an independent sequence for the same
// seed, so that a world generator can give every object its own stream and changing one object
// does not reshuffle the others.
class Rng {
public:
    explicit Rng(std::uint64_t seed, std::uint64_t stream = 0);

    std::uint64_t next_u64();
    float uniform();                    // [0, 1), 24 random bits
    float uniform(float lo, float hi);  // lo + (hi − lo) · uniform()
    int uniform_int(int lo, int hi);    // [lo, hi], both inclusive; lo <= hi
    // Approximately standard normal: the sum of four uniforms, centred and scaled to unit
    // variance (Irwin–Hall). Bounded to ±2√3, so a "3σ" jitter can never throw a leaf across the scene.
    float normal();
    bool chance(float probability);

private:
    std::uint64_t state_[4];
};

// ---- Builders -------------------------------------------------------------------------------
// Each returns the index range of the Gaussians it appended. `detail` (1 = the documented density,
// [kMinDetail, kMaxDetail]) multiplies the Gaussian count; surfaces keep covering at lower detail
// because their Gaussians grow by 1/√detail. Invalid arguments (non-finite or non-positive sizes,
// detail out of range, a size that would need more than 5e7 Gaussians) throw engine::Error naming
// the builder and the argument.

constexpr float kMinDetail = 0.01f;
constexpr float kMaxDetail = 16.0f;

struct IndexRange {
    std::size_t begin = 0;
    std::size_t end = 0;
    std::size_t size() const { return end - begin; }
};

enum class TreeKind {
    broadleaf,  // trunk forking into branches, a leaf clump at each branch tip
    conifer,    // straight trunk, a cone of leaf-covered whorls
};

struct TreeStyle {
    TreeKind kind = TreeKind::broadleaf;
    float detail = 1.0f;
    // Multiplies the leaf colours, e.g. (1.1, 1.0, 0.7) for an autumn-tinged tree.
    glm::vec3 leaf_tint{1.0f};
};

// Leaf Gaussians are flat ellipses: the long-axis scale (σ, exp(log_scale)) lies in
// [kLeafScaleMin, kLeafScaleMax] at every detail, the width is 0.5–0.9 × the length and the
// thickness is a tenth of the length. Opacity logits lie in [kLeafOpacityLogitMin, kLeafOpacityLogitMax].
constexpr float kLeafScaleMin = 0.01f;
constexpr float kLeafScaleMax = 0.04f;
constexpr float kLeafOpacityLogitMin = 2.0f;
constexpr float kLeafOpacityLogitMax = 5.0f;

struct TreeSplats {
    IndexRange bark;    // trunk and branches
    IndexRange leaves;  // directly after the bark
};

// A tree standing on `base` (the trunk's foot), `height` metres tall (2–8 m look right). At detail
// 1 a broadleaf tree has 650 × height² leaves (about 5,900 at 3 m, 20,000 at 5.6 m) and a conifer
// 600 × height²; the bark adds 20–25 %.
TreeSplats append_tree(SplatCloud& cloud, const glm::vec3& base, float height, Rng& rng, const TreeStyle& style = {});

// Picket boards: kPicketBoardWidth wide with kPicketGap between them (pitch = width + gap),
// centred along the fence line, pointed at the top, and two horizontal rails behind them, 2.5 cm
// towards up × (end − start) (on the left when walking from start to end). Boards are tiled with
// flat Gaussians on a regular grid, so they look solid close up and form a strict
// period-kPicketPitch pattern.
constexpr float kPicketBoardWidth = 0.08f;
constexpr float kPicketGap = 0.08f;
constexpr float kPicketPitch = kPicketBoardWidth + kPicketGap;

struct FenceSplats {
    IndexRange boards;
    IndexRange rails;  // directly after the boards
    int board_count = 0;
};

// `start` and `end` are on the ground and at least one pitch apart horizontally; `height` (at
// least 0.4 m) is the top of the boards above the ground. At detail 1 a board carries 25 Gaussians
// per 10 cm (5 columns, a row every 2 cm): 7.8 m of 0.9 m fence is 49 boards and about 12,000 Gaussians.
FenceSplats append_picket_fence(SplatCloud& cloud, const glm::vec3& start, const glm::vec3& end, float height, Rng& rng,
                                float detail = 1.0f);

// Grass blades standing on the plane y = centre.y: density × detail × π radius² blades, each two
// thin needle Gaussians (a straighter lower and a more bent upper segment), 3–28 cm tall. The
// patch has a ragged rim that reaches 0.7–1 × radius depending on direction; 1,200 blades per m²
// of the disc hide the ground.
IndexRange append_grass(SplatCloud& cloud, const glm::vec3& centre, float radius, float density, Rng& rng,
                        float detail = 1.0f);

// A flat disc of ground on the plane y = centre.y: overlapping flat Gaussians on a jittered grid
// (about 400 per square metre at detail 1, never fewer than about 10 per disc), earth with moss and
// darker soil patches. There are no holes at any detail: spacing and size change together.
IndexRange append_ground(SplatCloud& cloud, const glm::vec3& centre, float radius, Rng& rng, float detail = 1.0f);

// A lumpy, partly buried stone: flat grey Gaussians tangent to a noisy ellipsoid of the given
// half-extents, centred at `centre` (y of the ground plane under it). At detail 1 the ellipsoid's
// surface is sampled at 2,500 per m² and the samples below the ground are dropped (about half).
IndexRange append_rock(SplatCloud& cloud, const glm::vec3& centre, const glm::vec3& half_extents, Rng& rng,
                       float detail = 1.0f);

// ---- The evaluation scene -------------------------------------------------------------------

struct FineDetailOptions {
    std::uint64_t seed = 1;
    float detail = 1.0f;  // [kMinDetail, kMaxDetail]; the Gaussian count is roughly proportional
};

// A small garden about 10 m across centred on the origin, seen best from +z (e.g. eye (0, 2.2,
// 10.5) looking at (0, 1.6, 0)): a ground disc of radius 5 m, five trees 3–6 m tall (three
// broadleaf, two conifers), a 0.9 m picket fence across the front (z = 3.3 m, x in ±3.9 m, 49
// boards, rails on the garden side), six grass patches and three rocks. The layout is fixed; the
// seed changes shapes, colours and small offsets. At detail 1 it holds about 195,000 Gaussians
// (189,000–198,000 over seeds; leaves 35 %, grass 30 %, ground 16 %, bark 8 %, fence 6 %, rocks 4 %)
// and takes about 0.1 s to generate; the count is close to proportional to detail. The test bounds
// below leave room for tuning without letting the scene grow too large to bake and render on a CPU.
constexpr std::size_t kFineDetailGaussiansMin = 150'000;
constexpr std::size_t kFineDetailGaussiansMax = 250'000;

SplatCloud make_fine_detail_scene(const FineDetailOptions& options = {});

}  // namespace splat_lod::synth
