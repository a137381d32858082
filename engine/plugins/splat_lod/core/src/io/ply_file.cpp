#include "splat_lod/core/ply_file.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string_view>

#include "io_util.h"

namespace splat_lod::io {
namespace {

// Real splat headers are a few kilobytes; a file without end_header in the first MiB is not PLY.
constexpr std::size_t kMaxHeaderBytes = 1 << 20;

struct TypeName {
    std::string_view name;
    PlyType type;
};
constexpr std::array<TypeName, 16> kTypeNames{{
    {"char", PlyType::int8},
    {"int8", PlyType::int8},
    {"uchar", PlyType::uint8},
    {"uint8", PlyType::uint8},
    {"short", PlyType::int16},
    {"int16", PlyType::int16},
    {"ushort", PlyType::uint16},
    {"uint16", PlyType::uint16},
    {"int", PlyType::int32},
    {"int32", PlyType::int32},
    {"uint", PlyType::uint32},
    {"uint32", PlyType::uint32},
    {"float", PlyType::float32},
    {"float32", PlyType::float32},
    {"double", PlyType::float64},
    {"float64", PlyType::float64},
}};

bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

std::vector<std::string_view> split_words(std::string_view line) {
    std::vector<std::string_view> words;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && is_space(line[i])) ++i;
        const std::size_t start = i;
        while (i < line.size() && !is_space(line[i])) ++i;
        if (i > start) words.push_back(line.substr(start, i - start));
    }
    return words;
}

class HeaderParser {
public:
    HeaderParser(std::span<const std::uint8_t> bytes, const std::string& name) : bytes_(bytes), name_(name) {}

    PlyFile parse() {
        PlyFile ply;
        ply.name = name_;
        ply.bytes = bytes_;
        if (next_line() != "ply") fail_file(name_, "not a PLY file (first line is not \"ply\")");
        bool have_format = false;
        for (;;) {
            const std::string_view line = next_line();
            const auto words = split_words(line);
            if (words.empty()) continue;
            if (words[0] == "end_header") break;
            if (words[0] == "format") {
                parse_format(words, ply);
                have_format = true;
            } else if (words[0] == "comment" || words[0] == "obj_info") {
                ply.comments.emplace_back(line.substr(std::min(line.size(), words[0].size() + 1)));
            } else if (words[0] == "element") {
                parse_element(words, ply);
            } else if (words[0] == "property") {
                parse_property(words, ply);
            } else {
                fail_line("unexpected header line \"" + std::string(line) + "\"");
            }
        }
        if (!have_format) fail_file(name_, "PLY header has no format line");
        // Rows of no bytes need no data, so their count would be unchecked: a reader sizing its
        // output by it could be made to allocate anything.
        for (const auto& element : ply.elements)
            if (element.count > 0 && element.properties.empty())
                fail_file(name_, "element \"" + element.name + "\" has " + std::to_string(element.count) +
                                     " rows but no properties");
        ply.header_size = position_;
        return ply;
    }

private:
    std::string_view next_line() {
        const std::size_t limit = std::min(bytes_.size(), kMaxHeaderBytes);
        if (position_ >= limit) fail_file(name_, "PLY header has no end_header line");
        const auto* begin = bytes_.data() + position_;
        const auto* end = std::find(begin, bytes_.data() + limit, static_cast<std::uint8_t>('\n'));
        if (end == bytes_.data() + limit) fail_file(name_, "PLY header has no end_header line");
        std::string_view line(reinterpret_cast<const char*>(begin), static_cast<std::size_t>(end - begin));
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        position_ = static_cast<std::size_t>(end - bytes_.data()) + 1;
        ++line_number_;
        return line;
    }

    [[noreturn]] void fail_line(const std::string& message) const {
        fail_file(name_, "header line " + std::to_string(line_number_) + ": " + message);
    }

    void parse_format(const std::vector<std::string_view>& words, PlyFile& ply) const {
        if (words.size() != 3) fail_line("malformed format line");
        if (words[1] == "ascii")
            ply.format = PlyFormat::ascii;
        else if (words[1] == "binary_little_endian")
            ply.format = PlyFormat::binary_little_endian;
        else if (words[1] == "binary_big_endian")
            ply.format = PlyFormat::binary_big_endian;
        else
            fail_line("unknown format \"" + std::string(words[1]) + "\"");
        if (words[2] != "1.0") fail_line("unsupported PLY version \"" + std::string(words[2]) + "\"");
    }

    void parse_element(const std::vector<std::string_view>& words, PlyFile& ply) const {
        if (words.size() != 3) fail_line("malformed element line");
        PlyElement element;
        element.name = std::string(words[1]);
        const auto* first = words[2].data();
        const auto* last = first + words[2].size();
        const auto result = std::from_chars(first, last, element.count);
        if (result.ec != std::errc() || result.ptr != last)
            fail_line("element \"" + element.name + "\" has a bad count \"" + std::string(words[2]) + "\"");
        if (ply.find_element(element.name)) fail_line("duplicate element \"" + element.name + "\"");
        ply.elements.push_back(std::move(element));
    }

    void parse_property(const std::vector<std::string_view>& words, PlyFile& ply) const {
        if (ply.elements.empty()) fail_line("property before any element");
        if (words.size() >= 2 && words[1] == "list") fail_line("list properties are not supported");
        if (words.size() != 3) fail_line("malformed property line");
        const auto it =
            std::find_if(kTypeNames.begin(), kTypeNames.end(), [&](const TypeName& t) { return t.name == words[1]; });
        if (it == kTypeNames.end()) fail_line("unknown property type \"" + std::string(words[1]) + "\"");
        PlyElement& element = ply.elements.back();
        const std::string property_name(words[2]);
        if (element.find(property_name)) fail_line("duplicate property \"" + property_name + "\"");
        PlyProperty property{property_name, it->type, static_cast<std::uint32_t>(element.row_size)};
        element.row_size += ply_type_size(it->type);
        element.properties.push_back(std::move(property));
    }

    std::span<const std::uint8_t> bytes_;
    const std::string& name_;
    std::size_t position_ = 0;
    int line_number_ = 0;
};

void locate_binary_data(PlyFile& ply) {
    std::uint64_t offset = ply.header_size;
    for (auto& element : ply.elements) {
        element.data_offset = offset;
        const std::uint64_t size = checked_mul(element.count, element.row_size, ply.name, "element " + element.name);
        const std::uint64_t remaining = ply.bytes.size() - offset;
        if (size > remaining)
            fail_at(ply.name, offset,
                    "element \"" + element.name + "\" needs " + std::to_string(size) + " bytes (" +
                        std::to_string(element.count) + " rows of " + std::to_string(element.row_size) + ") but only " +
                        std::to_string(remaining) + " remain (truncated or wrong count)");
        offset += size;
    }
    if (offset < ply.bytes.size())
        ply.warnings.push_back(std::to_string(ply.bytes.size() - offset) + " bytes after the last element ignored");
}

void tokenise_ascii(PlyFile& ply) {
    std::uint64_t total = 0;
    for (auto& element : ply.elements) {
        element.data_offset = total;
        const std::uint64_t values = checked_mul(element.count, element.properties.size(), ply.name, element.name);
        total = checked_add(total, values, ply.name, "ascii values");
    }
    // Every value takes at least one character and one separator: cap the count before reserving.
    const std::uint64_t remaining = ply.bytes.size() - ply.header_size;
    if (total > remaining / 2 + 1)
        fail_at(ply.name, ply.header_size,
                "header declares " + std::to_string(total) + " ascii values but only " + std::to_string(remaining) +
                    " bytes follow (truncated or wrong count)");
    ply.ascii_values.reserve(static_cast<std::size_t>(total));
    const char* text = reinterpret_cast<const char*>(ply.bytes.data());
    std::size_t pos = static_cast<std::size_t>(ply.header_size);
    const std::size_t end = ply.bytes.size();
    while (ply.ascii_values.size() < total) {
        while (pos < end && is_space(text[pos])) ++pos;
        if (pos >= end)
            fail_at(ply.name, pos,
                    "ascii data end after " + std::to_string(ply.ascii_values.size()) + " of " + std::to_string(total) +
                        " values (truncated)");
        std::size_t stop = pos;
        while (stop < end && !is_space(text[stop])) ++stop;
        double value = 0.0;
        const auto result = std::from_chars(text + pos, text + stop, value);
        if (result.ec != std::errc() || result.ptr != text + stop)
            fail_at(ply.name, pos,
                    "bad ascii value \"" + std::string(text + pos, std::min<std::size_t>(stop - pos, 32)) + "\"");
        ply.ascii_values.push_back(value);
        pos = stop;
    }
    while (pos < end && is_space(text[pos])) ++pos;
    if (pos < end) ply.warnings.push_back("text after the last ascii value ignored");
}

template <typename T>
T load_value(const std::uint8_t* p, bool big_endian) {
    std::array<std::uint8_t, sizeof(T)> raw{};
    std::memcpy(raw.data(), p, sizeof(T));
    if (big_endian) std::reverse(raw.begin(), raw.end());
    T value;
    std::memcpy(&value, raw.data(), sizeof(T));
    return value;
}

template <typename T, typename Out>
void read_binary_column(const PlyFile& ply, const PlyElement& element, const PlyProperty& property,
                        std::vector<Out>& out) {
    const bool big_endian = ply.format == PlyFormat::binary_big_endian;
    const std::uint8_t* base = ply.bytes.data() + element.data_offset + property.offset;
    for (std::size_t r = 0; r < out.size(); ++r)
        out[r] = static_cast<Out>(load_value<T>(base + r * element.row_size, big_endian));
}

template <typename Out>
void read_column(const PlyFile& ply, const PlyElement& element, const PlyProperty& property, std::vector<Out>& out) {
    switch (property.type) {
        case PlyType::int8:
            return read_binary_column<std::int8_t>(ply, element, property, out);
        case PlyType::uint8:
            return read_binary_column<std::uint8_t>(ply, element, property, out);
        case PlyType::int16:
            return read_binary_column<std::int16_t>(ply, element, property, out);
        case PlyType::uint16:
            return read_binary_column<std::uint16_t>(ply, element, property, out);
        case PlyType::int32:
            return read_binary_column<std::int32_t>(ply, element, property, out);
        case PlyType::uint32:
            return read_binary_column<std::uint32_t>(ply, element, property, out);
        case PlyType::float32:
            return read_binary_column<float>(ply, element, property, out);
        case PlyType::float64:
            return read_binary_column<double>(ply, element, property, out);
    }
}

std::size_t property_index(const PlyElement& element, const PlyProperty& property) {
    return static_cast<std::size_t>(&property - element.properties.data());
}

}  // namespace

const PlyProperty* PlyElement::find(const std::string& property) const {
    for (const auto& p : properties)
        if (p.name == property) return &p;
    return nullptr;
}

const PlyElement* PlyFile::find_element(const std::string& element) const {
    for (const auto& e : elements)
        if (e.name == element) return &e;
    return nullptr;
}

std::vector<float> PlyFile::column_f32(const PlyElement& element, const PlyProperty& property) const {
    std::vector<float> out(static_cast<std::size_t>(element.count));
    if (format != PlyFormat::ascii) {
        read_column(*this, element, property, out);
        return out;
    }
    const std::size_t stride = element.properties.size();
    const std::size_t base = static_cast<std::size_t>(element.data_offset) + property_index(element, property);
    for (std::size_t r = 0; r < out.size(); ++r) out[r] = static_cast<float>(ascii_values[base + r * stride]);
    return out;
}

std::vector<std::uint32_t> PlyFile::column_u32(const PlyElement& element, const PlyProperty& property) const {
    if (property.type != PlyType::uint8 && property.type != PlyType::uint16 && property.type != PlyType::uint32)
        fail_file(name, "element \"" + element.name + "\" property \"" + property.name + "\" has type " +
                            ply_type_name(property.type) + ", expected an unsigned integer type");
    std::vector<std::uint32_t> out(static_cast<std::size_t>(element.count));
    if (format != PlyFormat::ascii) {
        read_column(*this, element, property, out);
        return out;
    }
    const std::size_t stride = element.properties.size();
    const std::size_t base = static_cast<std::size_t>(element.data_offset) + property_index(element, property);
    for (std::size_t r = 0; r < out.size(); ++r) {
        const double v = ascii_values[base + r * stride];
        if (!(v >= 0.0 && v <= 4294967295.0) || v != std::floor(v))
            fail_file(name, "element \"" + element.name + "\" row " + std::to_string(r) + " property \"" +
                                property.name + "\" is not an unsigned integer");
        out[r] = static_cast<std::uint32_t>(v);
    }
    return out;
}

const char* ply_type_name(PlyType type) {
    switch (type) {
        case PlyType::int8:
            return "char";
        case PlyType::uint8:
            return "uchar";
        case PlyType::int16:
            return "short";
        case PlyType::uint16:
            return "ushort";
        case PlyType::int32:
            return "int";
        case PlyType::uint32:
            return "uint";
        case PlyType::float32:
            return "float";
        case PlyType::float64:
            return "double";
    }
    return "?";
}

std::uint32_t ply_type_size(PlyType type) {
    switch (type) {
        case PlyType::int8:
        case PlyType::uint8:
            return 1;
        case PlyType::int16:
        case PlyType::uint16:
            return 2;
        case PlyType::int32:
        case PlyType::uint32:
        case PlyType::float32:
            return 4;
        case PlyType::float64:
            return 8;
    }
    return 0;
}

PlyFile parse_ply(std::span<const std::uint8_t> bytes, const std::string& name) {
    PlyFile ply = HeaderParser(bytes, name).parse();
    if (ply.format == PlyFormat::ascii)
        tokenise_ascii(ply);
    else
        locate_binary_data(ply);
    return ply;
}

}  // namespace splat_lod::io
