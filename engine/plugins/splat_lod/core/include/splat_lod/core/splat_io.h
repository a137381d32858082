#pragma once
// Readers and writers for Gaussian splat files. All readers are safe on hostile input: anything
// they cannot decode throws engine::Error whose message starts with the file name and, where it
// helps, the byte offset ("biker.spz: offset 112: zstd stream truncated"). Gaussians with NaN/Inf
// values or a zero quaternion are dropped and counted in the LoadReport; quaternions come back
// normalised. No reader converts axes: data come back in the file's own convention.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "splat_lod/core/splat_cloud.h"

namespace splat_lod {

enum class SplatFileFormat {
    ply,               // INRIA 3DGS PLY or PlayCanvas compressed PLY (told apart by the header)
    antimatter_splat,  // antimatter15 ".splat", 32 bytes per Gaussian
    spz,               // Niantic SPZ v2/v3 (gzip) or v4 (zstd streams)
    sog,               // PlayCanvas SOG: a folder (or its meta.json) with webp textures
    gltf,              // glTF 2.0 (.gltf, .glb) with KHR_gaussian_splatting primitives
    streamed_sog,      // PlayCanvas streamed SOG: lod-meta.json (or its folder), "#L" for level L
    tiles,             // several splat files read as one capture: a folder of them or a .txt list
    compact_chunk,     // a streamed world's compressed chunk file (compact_chunk.h), ".splatc"
};

// Decides by content first (PLY magic, gzip, NGSP, glTF magic, SPLATCZ1, folder/meta.json or lod-meta.json, a
// folder of tiles), then by extension (.splat, .gltf, .glb, .txt). Streamed SOGs and tiles are read
// through capture_source.h.
SplatFileFormat detect_splat_format(const std::filesystem::path& path);

// Reads any supported format; the report (if given) says which one.
SplatCloud load_splat_file(const std::filesystem::path& path, LoadReport* report = nullptr);

// The individual readers. The byte-span overloads take `name` for error messages.
SplatCloud read_ply(const std::filesystem::path& path, LoadReport* report = nullptr);
SplatCloud read_ply(std::span<const std::uint8_t> bytes, const std::string& name, LoadReport* report = nullptr);
SplatCloud read_antimatter_splat(const std::filesystem::path& path, LoadReport* report = nullptr);
SplatCloud read_antimatter_splat(std::span<const std::uint8_t> bytes, const std::string& name,
                                 LoadReport* report = nullptr);
SplatCloud read_spz(const std::filesystem::path& path, LoadReport* report = nullptr);
SplatCloud read_spz(std::span<const std::uint8_t> bytes, const std::string& name, LoadReport* report = nullptr);
// `path` is the SOG folder or its meta.json.
SplatCloud read_sog(const std::filesystem::path& path, LoadReport* report = nullptr);

// glTF 2.0 with KHR_gaussian_splatting (docs/gltf_splats.md): every splat primitive of the default
// scene's nodes, each node's world transform applied (positions and covariances; SH coefficients are
// not rotated), in one cloud. External buffers must lie in the file's folder; the byte-span overload
// allows none. SPZ-compressed primitives (KHR_gaussian_splatting_compression_spz_2) are read through
// read_spz and turned from SPZ's right-up-back axes into glTF's left-up-front ones.
SplatCloud read_gltf_splats(const std::filesystem::path& path, LoadReport* report = nullptr);
SplatCloud read_gltf_splats(std::span<const std::uint8_t> bytes, const std::string& name, LoadReport* report = nullptr);

// One POINTS primitive with float KHR_gaussian_splatting attributes at the cloud's SH degree, plus
// _SPLAT_LOD_COVERAGE_MIN/_MAX (float), _SPLAT_LOD_LEVEL (unsigned byte, byte stride 4) when has_lod_attributes() and
// _SPLAT_LOD_EXTRA_<name> (float) per extra property. `.glb` is binary, `.gltf` JSON with the buffer
// embedded as base64. Written through engine::write_file_atomic. A file read and written again gives
// the same bytes.
void write_gltf_splats(const std::filesystem::path& path, const SplatCloud& cloud);
std::vector<std::uint8_t> encode_gltf_splats(const SplatCloud& cloud, bool binary);

// By the name's extension: .glb and .gltf through write_gltf_splats, anything else through
// write_inria_ply.
void write_splat_file(const std::filesystem::path& path, const SplatCloud& cloud);

// Binary little-endian INRIA PLY: x y z nx ny nz f_dc_0..2 f_rest_* (45/24/9/0 by SH degree)
// opacity scale_0..2 rot_0..3, then the extra properties (float), then coverage_min,
// coverage_max (float) and lod_level (uchar) when has_lod_attributes(). Written through
// engine::write_file_atomic, so a failure never leaves a half-written file.
void write_inria_ply(const std::filesystem::path& path, const SplatCloud& cloud);
std::vector<std::uint8_t> encode_inria_ply(const SplatCloud& cloud);

// antimatter15 ".splat": position, linear scale (f32), RGBA8 (0.5 + C0·dc, sigmoid(opacity)),
// quaternion (w,x,y,z) as q·128+128 in u8. Lossy: SH rest, LOD attributes and extras are dropped.
void write_antimatter_splat(const std::filesystem::path& path, const SplatCloud& cloud);
std::vector<std::uint8_t> encode_antimatter_splat(const SplatCloud& cloud);

// SPZ stores right-up-back (RUB) axes; INRIA PLY scenes use right-down-forward (RDF). Flipping
// y and z is a 180° rotation about x: positions (x,-y,-z), quaternions (w,x,-y,-z), and the SH
// coefficients odd in y+z change sign. The map is its own inverse, so it converts either way.
void convert_spz_axes_to_ply(SplatCloud& cloud);

// Sign of SH coefficient k (1..15) under (x,y,z) -> (x,-y,-z): the parity of its y,z degree.
float sh_sign_under_yz_flip(int coeff);

// Opacity bytes and unit floats of 0 or 1 have no finite logit; readers clamp the opacity to
// [kOpacityClamp, 1 - kOpacityClamp] first (logit ±13.8), as PlayCanvas's tools do.
constexpr float kOpacityClamp = 1e-6f;
float opacity_to_logit(float opacity);

}  // namespace splat_lod
