// A capture listed as parts and read one part at a time (capture_source.h).
#include "splat_lod/core/capture_source.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

#include "engine/core/error.h"
#include "engine/core/file_io.h"
#include "engine/core/log.h"
#include "io_util.h"
#include "splat_lod/core/chunk_reader.h"
#include "splat_lod/core/ply_vertex_layout.h"
#include "splat_lod/core/splat_io.h"

namespace splat_lod {
namespace {

namespace fs = std::filesystem;

constexpr int kMaxListDepth = 8;  // a list naming a list naming … (cycles end here)

std::string lower_extension(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

bool is_tile_file(const fs::path& path) {
    const std::string ext = lower_extension(path);
    return ext == ".ply" || ext == ".spz" || ext == ".splat" || ext == ".glb" || ext == ".gltf";
}

bool is_sog_folder(const fs::path& path) {
    std::error_code ec;
    return fs::is_directory(path, ec) && fs::exists(path / "meta.json", ec);
}

bool is_tile_folder(const fs::path& path) {
    std::error_code ec;
    return fs::is_directory(path, ec) && !is_sog_folder(path) && !io::is_streamed_sog(path);
}

// A binary little-endian INRIA PLY with one element, cut into ranges; anything else is one part.
void add_file_parts(const fs::path& file, std::uint64_t max_records, std::vector<CapturePart>& parts) {
    std::error_code ec;
    const bool plain_ply = !fs::is_directory(file, ec) && detect_splat_format(file) == SplatFileFormat::ply;
    if (plain_ply) {
        io::PlyVertexLayout layout;
        bool single_element = true;
        try {
            layout = io::read_ply_vertex_layout(file);
        } catch (const engine::Error&) {
            single_element = false;  // compressed or ascii PLY: the whole-file reader says what is wrong
        }
        // Only a file exactly as long as its header says is cut (a lying count would make parts without
        // end); any other is read whole, and that reader names the problem.
        std::uint64_t records = 0, expected = 0;
        if (single_element &&
            (__builtin_mul_overflow(layout.vertex_count, layout.vertex_bytes, &records) ||
             __builtin_add_overflow(records, layout.header_bytes, &expected) || expected != layout.file_bytes))
            single_element = false;
        if (single_element && layout.vertex_count > max_records) {
            for (std::uint64_t begin = 0; begin < layout.vertex_count; begin += max_records) {
                CapturePart part;
                part.kind = CapturePart::Kind::ply_records;
                part.file = file;
                part.begin = begin;
                part.end = std::min(layout.vertex_count, begin + max_records);
                part.gaussians = part.end - part.begin;
                parts.push_back(std::move(part));
            }
            return;
        }
        if (single_element) {
            CapturePart part;
            part.file = file;
            part.gaussians = layout.vertex_count;
            parts.push_back(std::move(part));
            return;
        }
    }
    CapturePart part;
    part.file = file;
    parts.push_back(std::move(part));
}

void add_streamed_sog_parts(const fs::path& meta, int level, std::vector<CapturePart>& parts) {
    const io::StreamedSog sog = io::read_streamed_sog_meta(meta);
    const io::StreamedSogLevel& chosen = io::streamed_sog_level(sog, level < 0 ? 0 : level);
    for (const io::StreamedSogFile& file : chosen.files) {
        CapturePart part;
        part.kind = CapturePart::Kind::sog_ranges;
        part.file = file.file;
        part.sog = file;
        part.gaussians = file.gaussians;
        parts.push_back(std::move(part));
    }
}

void add_parts(const fs::path& path, std::uint64_t max_records, int depth, std::vector<CapturePart>& parts);

bool is_world_manifest(const fs::path& path) {
    return path.filename() == world::kManifestFileName;
}

void add_world_parts(const fs::path& manifest_path, std::vector<CapturePart>& parts) {
    const world::WorldManifest manifest = world::read_world_manifest(manifest_path);
    for (const world::ChunkEntry& entry : manifest.chunks) {
        CapturePart part;
        part.kind = CapturePart::Kind::world_chunk;
        part.file = manifest_path.parent_path() / entry.file;
        part.chunk = std::make_shared<const world::ChunkEntry>(entry);
        parts.push_back(std::move(part));
    }
    if (parts.empty()) io::fail_file(manifest_path.string(), "the world has no chunk");
}

// A world chunk's finest Gaussians as the capture they were baked from.
SplatCloud read_world_chunk(const CapturePart& part, LoadReport* report) {
    SplatCloud cloud = world::read_chunk_prefix(part.file, *part.chunk, 1);
    std::vector<std::uint8_t> keep(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) keep[i] = cloud.lod_level[i] == 1;
    cloud.keep_only(keep);
    std::fill(cloud.coverage_min.begin(), cloud.coverage_min.end(), -1.0f);
    std::fill(cloud.coverage_max.begin(), cloud.coverage_max.end(), -1.0f);
    if (report) {
        *report = LoadReport{};
        report->format = "world chunk (bake level 1)";
        report->gaussians_in_file = report->loaded = cloud.size();
    }
    return cloud;
}

// The folder's tiles in name order: splat files and SOG folders (plain or streamed).
void add_folder_parts(const fs::path& folder, std::uint64_t max_records, int depth, std::vector<CapturePart>& parts) {
    std::vector<fs::path> entries;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(folder, ec))
        if ((entry.is_regular_file() && is_tile_file(entry.path())) || is_sog_folder(entry.path()) ||
            (entry.is_directory() && io::is_streamed_sog(entry.path())))
            entries.push_back(entry.path());
    if (ec) io::fail_file(folder.string(), "cannot list the folder: " + ec.message());
    if (entries.empty())
        io::fail_file(folder.string(),
                      "holds no splat tile (.ply, .spz, .splat, .glb, .gltf, or a SOG folder with meta.json or "
                      "lod-meta.json)");
    std::sort(entries.begin(), entries.end());
    for (const fs::path& entry : entries) add_parts(entry, max_records, depth + 1, parts);
}

void add_list_parts(const fs::path& list, std::uint64_t max_records, int depth, std::vector<CapturePart>& parts) {
    std::istringstream text(engine::read_text_file(list));
    std::string line;
    int number = 0, named = 0;
    while (std::getline(text, line)) {
        ++number;
        while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
        const auto start = line.find_first_not_of(" \t");
        if (start == std::string::npos || line[start] == '#') continue;
        const fs::path entry = list.parent_path() / line.substr(start);
        try {
            add_parts(entry, max_records, depth + 1, parts);
        } catch (const engine::Error& e) {
            io::fail_file(list.string(), "line " + std::to_string(number) + ": " + e.what());
        }
        ++named;
    }
    if (named == 0) io::fail_file(list.string(), "the tile list names no file");
}

void add_parts(const fs::path& given, std::uint64_t max_records, int depth, std::vector<CapturePart>& parts) {
    if (depth > kMaxListDepth)
        io::fail_file(given.string(), "tile lists and folders nest deeper than " + std::to_string(kMaxListDepth));
    int level = -1;
    const fs::path path = capture_file_and_level(given, &level);
    std::error_code ec;
    if (!fs::exists(path, ec)) io::fail_file(path.string(), "no such file or folder");
    if (io::is_streamed_sog(path)) return add_streamed_sog_parts(path, level, parts);
    if (level >= 0) io::fail_file(given.string(), "\"#level\" is only for a streamed SOG's lod-meta.json");
    if (is_world_manifest(path)) return add_world_parts(path, parts);
    if (is_tile_folder(path)) return add_folder_parts(path, max_records, depth, parts);
    if (!fs::is_directory(path, ec) && lower_extension(path) == ".txt")
        return add_list_parts(path, max_records, depth, parts);
    add_file_parts(path, max_records, parts);
}

SplatCloud read_ply_records(const CapturePart& part, LoadReport* report) {
    const io::PlyVertexLayout layout = io::read_ply_vertex_layout(part.file);
    const std::string name = part.file.string();
    if (part.end > layout.vertex_count || part.begin > part.end)
        io::fail_file(name, "records " + std::to_string(part.begin) + ".." + std::to_string(part.end) +
                                " are not within its " + std::to_string(layout.vertex_count));
    const std::string header = io::header_with_vertex_count(layout, part.end - part.begin);
    const std::uint64_t offset = layout.header_bytes + part.begin * layout.vertex_bytes;
    const std::uint64_t size = (part.end - part.begin) * layout.vertex_bytes;
    std::vector<std::uint8_t> bytes(header.size() + static_cast<std::size_t>(size));
    std::copy(header.begin(), header.end(), bytes.begin());
    std::ifstream in(part.file, std::ios::binary);
    if (!in) io::fail_file(name, "cannot open");
    in.seekg(static_cast<std::streamoff>(offset));
    in.read(reinterpret_cast<char*>(bytes.data() + header.size()), static_cast<std::streamsize>(size));
    if (static_cast<std::uint64_t>(in.gcount()) != size)
        io::fail_at(name, offset,
                    "the file ends before record " + std::to_string(part.end) + " of " +
                        std::to_string(layout.vertex_count) + " (truncated)");
    return read_ply(bytes, name + " records " + std::to_string(part.begin) + ".." + std::to_string(part.end), report);
}

}  // namespace

std::string CapturePart::label() const {
    switch (kind) {
        case Kind::ply_records:
            return file.string() + " records " + std::to_string(begin) + ".." + std::to_string(end);
        case Kind::sog_ranges:
            return file.string() + " (" + std::to_string(sog.ranges.size()) + " ranges)";
        case Kind::world_chunk:
        case Kind::whole_file:
            break;
    }
    return file.string();
}

std::uint64_t Capture::gaussians() const {
    std::uint64_t total = 0;
    for (const CapturePart& part : parts) total += part.gaussians;
    return total;
}

fs::path capture_file_and_level(const fs::path& path, int* level) {
    *level = -1;
    const std::string text = path.string();
    const auto hash = text.rfind('#'), slash = text.rfind('/');
    if (hash == std::string::npos || (slash != std::string::npos && hash < slash)) return path;
    std::error_code ec;
    if (fs::exists(path, ec)) return path;  // a file whose name holds '#'
    const std::string digits = text.substr(hash + 1);
    if (digits.empty() || digits.size() > 2 || digits.find_first_not_of("0123456789") != std::string::npos)
        io::fail_file(text, "\"#" + digits + "\" is not a level number (\"lod-meta.json#0\" is the finest)");
    *level = std::stoi(digits);
    return fs::path(text.substr(0, hash));
}

bool is_multi_part_capture(const fs::path& given) {
    int level = -1;
    const fs::path path = capture_file_and_level(given, &level);
    std::error_code ec;
    if (level >= 0 || io::is_streamed_sog(path)) return true;
    if (!fs::exists(path, ec)) return false;
    if (is_world_manifest(path)) return true;
    return is_tile_folder(path) || (!fs::is_directory(path, ec) && lower_extension(path) == ".txt");
}

Capture open_capture(const fs::path& path, std::uint64_t max_part_records) {
    if (max_part_records == 0) engine::fail("splat_lod::open_capture(): max_part_records must be positive");
    Capture capture;
    capture.path = path;
    add_parts(path, max_part_records, 0, capture.parts);
    int level = -1;
    const fs::path file = capture_file_and_level(path, &level);
    if (io::is_streamed_sog(file))
        capture.description = "streamed SOG level " + std::to_string(std::max(level, 0)) + ": " +
                              std::to_string(capture.parts.size()) + " chunk files";
    else if (is_multi_part_capture(path))
        capture.description = std::to_string(capture.parts.size()) + " tile parts";
    else
        capture.description = std::to_string(capture.parts.size()) + " part(s) of one file";
    return capture;
}

SplatCloud read_capture_part(const CapturePart& part, LoadReport* report) {
    switch (part.kind) {
        case CapturePart::Kind::ply_records:
            return read_ply_records(part, report);
        case CapturePart::Kind::sog_ranges:
            return io::read_streamed_sog_file(part.sog, report);
        case CapturePart::Kind::world_chunk:
            return read_world_chunk(part, report);
        case CapturePart::Kind::whole_file:
            break;
    }
    return load_splat_file(part.file, report);
}

void merge_load_report(LoadReport& total, const LoadReport& part) {
    if (total.format.empty()) total.format = part.format;
    total.gaussians_in_file += part.gaussians_in_file;
    total.loaded += part.loaded;
    total.dropped_non_finite += part.dropped_non_finite;
    total.dropped_zero_rotation += part.dropped_zero_rotation;
    total.warnings.insert(total.warnings.end(), part.warnings.begin(), part.warnings.end());
    total.antialiased = total.antialiased || part.antialiased;
}

SplatCloud read_capture(const fs::path& path, LoadReport* report) {
    const Capture capture = open_capture(path);
    SplatCloud whole;
    LoadReport total;
    for (const CapturePart& part : capture.parts) {
        LoadReport part_report;
        append_cloud(whole, read_capture_part(part, &part_report));
        merge_load_report(total, part_report);
    }
    total.format = capture.description + " (" + total.format + ")";
    total.loaded = whole.size();
    if (report) {
        *report = std::move(total);
        return whole;
    }
    for (const auto& warning : total.warnings) engine::log_warning(path.string() + ": " + warning);
    if (total.dropped() > 0)
        engine::log_warning(path.string() + ": dropped " + std::to_string(total.dropped_non_finite) +
                            " Gaussians with NaN/Inf values and " + std::to_string(total.dropped_zero_rotation) +
                            " with a zero quaternion");
    return whole;
}

}  // namespace splat_lod
