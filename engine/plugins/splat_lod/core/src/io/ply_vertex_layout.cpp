// The header of a single-element binary PLY, read without its data (io/ply_vertex_layout.h).
#include "splat_lod/core/ply_vertex_layout.h"

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <span>
#include <system_error>
#include <vector>

#include "io_util.h"
#include "splat_lod/core/ply_file.h"

namespace splat_lod::io {
namespace {

// The same cap as parse_ply: real splat headers are a few kilobytes.
constexpr std::size_t kMaxHeaderBytes = 1 << 20;

// The header text up to and including its "end_header" line, read a block at a time.
std::string read_header_text(std::ifstream& in, const std::string& name) {
    std::string text;
    std::size_t line_start = 0;
    char block[4096];
    while (text.size() < kMaxHeaderBytes) {
        in.read(block, sizeof block);
        const auto got = static_cast<std::size_t>(in.gcount());
        if (got == 0) break;
        text.append(block, got);
        for (std::size_t newline = text.find('\n', line_start); newline != std::string::npos;
             newline = text.find('\n', line_start)) {
            std::string_view line(text.data() + line_start, newline - line_start);
            if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
            line_start = newline + 1;
            if (line == "end_header") {
                text.resize(line_start);
                return text;
            }
        }
    }
    fail_file(name, text.rfind("ply", 0) == 0 ? "PLY header has no end_header line" : "not a PLY file");
}

// The "element vertex N" line: its offset and length in the header, and N.
struct VertexLine {
    std::size_t offset = 0, length = 0;
    std::uint64_t count = 0;
};

VertexLine find_vertex_line(const std::string& header, const std::string& name) {
    const std::string prefix = "\nelement vertex ";
    const std::size_t at = header.find(prefix);
    if (at == std::string::npos) fail_file(name, "PLY header has no \"element vertex <count>\" line");
    VertexLine line;
    line.offset = at + 1;
    const std::size_t digits = at + prefix.size();
    const std::size_t end = header.find_first_of("\r\n", digits);
    line.length = end - line.offset;
    const auto result = std::from_chars(header.data() + digits, header.data() + end, line.count);
    if (result.ec != std::errc() || result.ptr != header.data() + end)
        fail_file(name, "PLY header has a bad vertex count \"" + header.substr(digits, end - digits) + "\"");
    return line;
}

}  // namespace

std::string header_with_vertex_count(const PlyVertexLayout& layout, std::uint64_t count) {
    const VertexLine line = find_vertex_line(layout.header, "PLY header");
    std::string header = layout.header;
    header.replace(line.offset, line.length, "element vertex " + std::to_string(count));
    return header;
}

PlyVertexLayout read_ply_vertex_layout(const std::filesystem::path& path) {
    const std::string name = path.string();
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) fail_file(name, "is a directory, not a file");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail_file(name, std::string("cannot open: ") + std::strerror(errno));
    PlyVertexLayout layout;
    layout.file_bytes = std::filesystem::file_size(path, ec);
    if (ec) fail_file(name, "cannot read its size: " + ec.message());
    layout.header = read_header_text(in, name);
    layout.header_bytes = layout.header.size();
    layout.vertex_count = find_vertex_line(layout.header, name).count;

    // parse_ply checks every other header rule; with a count of 0 it needs no data.
    const std::string empty = header_with_vertex_count(layout, 0);
    const PlyFile ply = parse_ply(std::span(reinterpret_cast<const std::uint8_t*>(empty.data()), empty.size()), name);
    if (ply.format != PlyFormat::binary_little_endian) fail_file(name, "expected a binary_little_endian PLY");
    if (ply.elements.size() != 1 || ply.elements[0].name != "vertex")
        fail_file(name, "expected a PLY whose only element is \"vertex\"");
    layout.vertex_bytes = ply.elements[0].row_size;
    if (layout.vertex_bytes == 0) fail_file(name, "the vertex element has no properties");
    return layout;
}

}  // namespace splat_lod::io
