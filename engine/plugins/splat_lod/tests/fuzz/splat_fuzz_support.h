#pragma once
// The splat_lod harnesses' own checks (README.md here), on top of the engine's fuzz_support.h, whose
// names (require, finite, sandbox_dir, ...) splat_fuzz:: also answers to.
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/core/error.h"
#include "fuzz_support.h"
#include "splat_lod/core/splat_cloud.h"

namespace splat_fuzz {

using namespace engine_fuzz;

// What splat_io.h promises of every cloud a reader returns: consistent arrays, no NaN/Inf in any
// attribute, unit quaternions, and a report whose counts add up.
void check_cloud(const splat_lod::SplatCloud& cloud, const splat_lod::LoadReport& report);

// One splat reader's byte-span overload on the input (read(bytes, name, &report)): an engine::Error
// must name the file, a returned cloud must keep check_cloud's promises.
template <class Read>
int fuzz_splat_reader(const std::uint8_t* data, std::size_t size, const std::string& name, Read read) {
    splat_lod::LoadReport report;
    splat_lod::SplatCloud cloud;
    try {
        cloud = read(bytes_of(data, size), name, &report);
    } catch (const engine::Error& e) {  // anything else escapes: a finding
        check_error_names(e, name);
        return 0;
    }
    check_cloud(cloud, report);
    return 0;
}

// The engine's sandbox files and, beside them:
//   cloud.ply      a 3-Gaussian INRIA PLY (SH degree 1);  cloud.splat  the same as .splat
void write_sandbox_assets();

}  // namespace splat_fuzz
