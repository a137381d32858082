#pragma once
// The profile's plots through gnuplot: the numbers go to lod.dat and baseline.dat, the drawing to
// plots.gp (all kept in the output folder, so a plot can be restyled and redrawn with
// `gnuplot plots.gp` there):
//   frame_time.png  frame time along the path, LOD+streaming against baseline, segments shaded,
//                   camera height on the right axis;
//   memory.png      resident GPU memory against the memory budget (top) and bytes uploaded per
//                   frame against the upload budget (bottom);
//   gaussians.png   Gaussians drawn per LOD level along the path (and the baseline's total).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sample_game/harness/frame_record.h"

namespace sample_game {

struct PlotResult {
    std::vector<std::filesystem::path> pictures;  // empty when gnuplot is missing
    std::string problem;  // why there are no pictures ("gnuplot not found; install gnuplot-nox ...")
};

// Throws engine::Error when gnuplot runs but fails (naming the script); a missing gnuplot is not an
// error here (the CSV is the result, the plots a view of it): it is reported in PlotResult::problem.
PlotResult write_profile_plots(const std::filesystem::path& folder, const std::vector<FrameRecord>& lod,
                               const std::vector<FrameRecord>& baseline, std::uint64_t memory_budget_bytes,
                               std::uint64_t upload_budget_bytes);

}  // namespace sample_game
