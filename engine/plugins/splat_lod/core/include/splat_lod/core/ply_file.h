#pragma once
// A generic PLY parser: the header's elements and properties, and typed column access to the
// data that follows. Binary (either byte order) is read in place; ascii is tokenised once.
// List properties are rejected: no splat format uses them and they make rows variable-sized.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace splat_lod::io {

enum class PlyType : std::uint8_t { int8, uint8, int16, uint16, int32, uint32, float32, float64 };
enum class PlyFormat : std::uint8_t { ascii, binary_little_endian, binary_big_endian };

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::float32;
    std::uint32_t offset = 0;  // byte offset inside a binary row
};

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::vector<PlyProperty> properties;
    std::uint64_t row_size = 0;     // bytes per row in binary files
    std::uint64_t data_offset = 0;  // file offset of the first row (binary) / first value index (ascii)

    const PlyProperty* find(const std::string& property) const;
};

struct PlyFile {
    std::string name;  // for messages
    PlyFormat format = PlyFormat::binary_little_endian;
    std::vector<PlyElement> elements;
    std::vector<std::string> comments;
    std::vector<std::string> warnings;  // e.g. trailing bytes after the last element
    std::span<const std::uint8_t> bytes;
    std::uint64_t header_size = 0;
    std::vector<double> ascii_values;  // every value of an ascii file, in file order

    const PlyElement* find_element(const std::string& element) const;

    // The property converted for every row. Integer types convert exactly to float up to 2^24.
    std::vector<float> column_f32(const PlyElement& element, const PlyProperty& property) const;
    // Integer properties only; a float property here is an error naming it.
    std::vector<std::uint32_t> column_u32(const PlyElement& element, const PlyProperty& property) const;
};

const char* ply_type_name(PlyType type);
std::uint32_t ply_type_size(PlyType type);

// Parses the header and checks that the data are as large as it says (with 64-bit checked
// sizes). `bytes` must outlive the result.
PlyFile parse_ply(std::span<const std::uint8_t> bytes, const std::string& name);

}  // namespace splat_lod::io
