#pragma once
// Internal entry points shared between the reader translation units.
#include <filesystem>
#include <string>

#include "splat_lod/core/ply_file.h"
#include "splat_lod/core/splat_cloud.h"

namespace splat_lod::io {

// INRIA layout: the full or reduced vertex element, with extra properties kept.
SplatCloud decode_inria_ply(const PlyFile& ply, LoadReport& report);

// PlayCanvas compressed layout: "chunk" + packed "vertex" (+ optional "sh").
bool is_compressed_ply(const PlyFile& ply);
SplatCloud decode_compressed_ply(const PlyFile& ply, LoadReport& report);

// PlayCanvas SOG (the folder or its meta.json) decoded without finish_load: the texels in file order,
// bad ones still in place (the streamed SOG reader selects record ranges by position first).
SplatCloud decode_sog(const std::filesystem::path& path, LoadReport& report);

// Drops bad Gaussians, then hands the report to the caller, or logs its warnings and drop counts
// when the caller did not ask for one (so that nothing is lost silently).
void finish_load(SplatCloud& cloud, LoadReport& report, LoadReport* caller, const std::string& name);

}  // namespace splat_lod::io
