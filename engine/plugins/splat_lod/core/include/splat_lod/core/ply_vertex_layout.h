#pragma once
// The byte layout of a binary little-endian PLY whose only element is "vertex" (the INRIA files
// write_inria_ply makes), read from the header alone, so that a caller can seek to any record and
// read a range of them without loading the file (the world streamer's chunk prefixes).
#include <cstdint>
#include <filesystem>
#include <string>

namespace splat_lod::io {

struct PlyVertexLayout {
    std::string header;              // the header text, "ply\n" … "end_header\n"
    std::uint64_t header_bytes = 0;  // = header.size(): the file offset of the first record
    std::uint64_t vertex_bytes = 0;  // bytes per record
    std::uint64_t vertex_count = 0;
    std::uint64_t file_bytes = 0;  // the file's size on disk
};

// Reads and checks the header of `path` (parse_ply's rules, plus: binary little-endian, a single
// "vertex" element). Does not check that the records are all there: compare file_bytes with
// header_bytes + vertex_count · vertex_bytes where that matters. Errors name the file.
PlyVertexLayout read_ply_vertex_layout(const std::filesystem::path& path);

// The same header declaring `count` vertices (the element line rewritten), for decoding a range
// of records with the whole-file reader.
std::string header_with_vertex_count(const PlyVertexLayout& layout, std::uint64_t count);

}  // namespace splat_lod::io
