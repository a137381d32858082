#pragma once
// The soak run (`sample_game_harness --soak`): walks the camera path again and again with LOD and
// streaming, as a player leaving the game running would, and checks that nothing grows and that
// streaming survives chunk files that go wrong underneath it.
//
// Each lap walks the whole path (which ends where it starts), then settles: it keeps updating at
// the last pose until nothing is being read or uploaded and no chunk is failed (at most 400
// updates, so the streamer's retry must come within 300 frames) and measures there, so every lap ends in the same place
// and state:
//   - the GL objects the driver holds (engine/gl/gl_census.h: counts per kind, buffer and texture
//     bytes), the process's resident memory (RSS; on llvmpipe this includes the "GPU" memory),
//     the streamer's resident bytes and failed chunks, and the frame itself.
// With faults on, the run streams from a linked copy of the world (<out>/world_copy, chunk_faults.h)
// and, on every lap but the first and the last, damages the files of four chunks while the camera
// is away (from 45 % of the lap to its end): of the chunks that lost levels since the last lap end, the
// four nearest the path's start (so the camera's return reads them again while they are damaged):
// one removed, one truncated, one replaced by the farthest chunk's file, one corrupted at the same
// size (bits flipped that only the manifest's checksums show). The files are restored
// when the walk ends, and the streamer's retry (GameSettings::retry_failed_after_frames) must bring the chunks back.
//
// Checks (PASS/FAIL lines in <out>/soak_summary.txt):
//   1. GL objects: every lap end holds exactly the objects of the first lap end;
//   2. GL memory: buffer + texture bytes at the last lap end within 1 MiB of the reference lap end
//      (the second, or the first of a shorter run);
//   3. CPU memory: RSS at the last lap end within 16 MiB + 2 % of the reference lap end;
//   4. streaming recovers: no chunk failed at the last lap end, and the streamed resident bytes
//      equal the reference lap end's within 1 %;
//   5. faults are noticed (with faults on): each kind made at least one chunk fail, and no chunk
//      that was not damaged failed;
//   6. no lasting damage on screen: every lap end's frame is within 40 dB PSNR of the first's.
// Outputs: soak.csv (a row every sample_every frames and one per lap end), soak_summary.txt,
// soak_memory.png and soak_objects.png (gnuplot), lap_end_<k>.png of the first and last lap ends.
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "sample_game/game_settings.h"

namespace sample_game {

struct SoakOptions {
    std::filesystem::path world;  // folder holding world.json (never modified)
    std::filesystem::path out = "out/soak";
    int width = 320, height = 180;
    int frames_per_lap = 200;
    int laps = 10;
    bool faults = true;
    int sample_every = 10;
    GameSettings settings;  // the run uses settings.retry_failed_after_frames as given
    // Called after each lap's walk, before it settles and is measured (tests: make a leak to see the
    // checks catch it). May be empty.
    std::function<void(int lap)> after_lap;
};

struct SoakLapEnd {
    int lap = 0;
    std::uint64_t frame = 0;
    std::uint32_t gl_objects = 0;
    std::uint64_t gl_bytes = 0, rss_bytes = 0, streamed_bytes = 0;
    std::uint32_t failed_chunks = 0, settle_updates = 0;
    double psnr_vs_first = 0.0;  // +inf when identical
    std::string gl_census;       // GlCensus::describe()
};

struct SoakOutcome {
    std::vector<SoakLapEnd> lap_ends;
    std::vector<std::string> checks;  // "PASS ..." / "FAIL ..."
    bool passed = false;
    std::uint64_t failures_removed = 0, failures_truncated = 0, failures_replaced = 0, failures_corrupted = 0;
    std::uint64_t failures_undamaged = 0;
    std::string summary_text;  // also in <out>/soak_summary.txt
    std::string plot_problem;
};

// Throws engine::Error naming the option ("sample_game_harness: --laps must be at least 3 with faults").
void validate(const SoakOptions& options);

// Progress lines go to `progress` (may be null). Needs a current GL context. Failed checks are
// results (outcome.passed), not errors.
SoakOutcome run_soak(const SoakOptions& options, std::FILE* progress);

}  // namespace sample_game
