// PLY reader (ASCII and binary, either byte order): the header's elements and properties, then
// the vertex positions and face lists, every other element and property skipped.
#include <fmt/format.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/io/surface_files.hpp"

namespace slc {
namespace {

enum class Format { ascii, little, big };

/// A scalar type of the PLY format.
struct Type {
    int size = 0;  ///< bytes in binary files
    bool is_float = false;
    bool is_signed = false;
};

bool type_named(std::string_view name, Type& t) {
    struct Named {
        std::string_view name;
        Type type;
    };
    static constexpr Named types[] = {
        {"char", {1, false, true}},    {"int8", {1, false, true}},    {"uchar", {1, false, false}},
        {"uint8", {1, false, false}},  {"short", {2, false, true}},   {"int16", {2, false, true}},
        {"ushort", {2, false, false}}, {"uint16", {2, false, false}}, {"int", {4, false, true}},
        {"int32", {4, false, true}},   {"uint", {4, false, false}},   {"uint32", {4, false, false}},
        {"float", {4, true, true}},    {"float32", {4, true, true}},  {"double", {8, true, true}},
        {"float64", {8, true, true}}};
    for (const Named& n : types) {
        if (n.name == name) {
            t = n.type;
            return true;
        }
    }
    return false;
}

struct Property {
    std::string name;
    Type type;  ///< the value type (of the items, for a list)
    bool is_list = false;
    Type count_type;  ///< the type of a list's length
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
};

std::vector<std::string_view> split(std::string_view line) {
    std::vector<std::string_view> out;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        const std::size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
        if (i > start) out.push_back(line.substr(start, i - start));
    }
    return out;
}

/// Reads the values of the body one at a time, as text words or as binary numbers.
class Body {
public:
    Body(std::string_view data, Format format, const std::string& source)
        : data_(data), format_(format), source_(source) {}

    /// The next value of type t, as a double (exact for every integer type of PLY).
    double next(Type t, const std::string& where) {
        if (format_ == Format::ascii) return next_word(t, where);
        if (data_.size() < static_cast<std::size_t>(t.size))
            throw InvalidInput(fmt::format("{}: the data ends early, in {}", source_, where));
        std::uint64_t u = 0;
        for (int i = 0; i < t.size; ++i) {
            const int at = format_ == Format::little ? t.size - 1 - i : i;
            u = (u << 8) | static_cast<unsigned char>(data_[static_cast<std::size_t>(at)]);
        }
        data_.remove_prefix(static_cast<std::size_t>(t.size));
        if (t.is_float) {
            return t.size == 4
                       ? static_cast<double>(std::bit_cast<float>(static_cast<std::uint32_t>(u)))
                       : std::bit_cast<double>(u);
        }
        if (!t.is_signed) return static_cast<double>(u);
        const int shift = 64 - 8 * t.size;  // sign-extend
        return static_cast<double>(static_cast<std::int64_t>(u << shift) >> shift);
    }

private:
    double next_word(Type t, const std::string& where) {
        std::size_t i = 0;
        while (i < data_.size() && std::strchr(" \t\r\n", data_[i]) != nullptr) ++i;
        std::size_t j = i;
        while (j < data_.size() && std::strchr(" \t\r\n", data_[j]) == nullptr) ++j;
        if (i == j)
            throw InvalidInput(fmt::format("{}: the data ends early, in {}", source_, where));
        const std::string_view word = data_.substr(i, j - i);
        data_.remove_prefix(j);
        double value = 0.0;
        bool ok = false;
        if (t.is_float) {
            const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
            ok = ec == std::errc{} && end == word.data() + word.size();
        } else {
            long long v = 0;
            const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), v);
            ok = ec == std::errc{} && end == word.data() + word.size();
            value = static_cast<double>(v);
        }
        if (!ok) {
            throw InvalidInput(
                fmt::format("{}: {}: a value is not a number of its type", source_, where));
        }
        return value;
    }

    std::string_view data_;
    Format format_;
    const std::string& source_;
};

}  // namespace

Surface parse_ply(std::string_view bytes, const std::string& source) {
    // The header: lines up to "end_header".
    std::vector<Element> elements;
    Format format = Format::ascii;
    bool has_format = false;
    std::size_t at = 0;
    for (std::size_t number = 1;; ++number) {
        const std::size_t newline = bytes.find('\n', at);
        if (newline == std::string_view::npos)
            throw InvalidInput(fmt::format("{}: the PLY header has no end_header line", source));
        const auto w = split(bytes.substr(at, newline - at));
        at = newline + 1;
        const std::string place = fmt::format("{}, line {}", source, number);
        if (number == 1) {
            if (w.size() != 1 || w[0] != "ply")
                throw InvalidInput(fmt::format("{}: a PLY file begins with \"ply\"", place));
            continue;
        }
        if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
        if (w[0] == "end_header") break;
        if (w[0] == "format") {
            if (w.size() != 3 || w[2] != "1.0")
                throw InvalidInput(fmt::format("{}: expected \"format TYPE 1.0\"", place));
            if (w[1] == "ascii") {
                format = Format::ascii;
            } else if (w[1] == "binary_little_endian") {
                format = Format::little;
            } else if (w[1] == "binary_big_endian") {
                format = Format::big;
            } else {
                throw InvalidInput(fmt::format("{}: unknown format", place));
            }
            has_format = true;
        } else if (w[0] == "element") {
            unsigned long long count = 0;
            if (w.size() != 3 ||
                std::from_chars(w[2].data(), w[2].data() + w[2].size(), count).ptr !=
                    w[2].data() + w[2].size() ||
                count > 0xffffffffull) {
                throw InvalidInput(fmt::format("{}: expected \"element NAME COUNT\"", place));
            }
            elements.push_back({std::string(w[1]), count, {}});
        } else if (w[0] == "property") {
            if (elements.empty())
                throw InvalidInput(fmt::format("{}: a property before any element", place));
            Property p;
            bool ok = false;
            if (w.size() == 3) {
                ok = type_named(w[1], p.type);
                p.name = w[2];
            } else if (w.size() == 5 && w[1] == "list") {
                ok = type_named(w[2], p.count_type) && !p.count_type.is_float &&
                     type_named(w[3], p.type);
                p.is_list = true;
                p.name = w[4];
            }
            if (!ok) throw InvalidInput(fmt::format("{}: a malformed property", place));
            elements.back().properties.push_back(p);
        } else {
            throw InvalidInput(fmt::format("{}: unexpected header line", place));
        }
    }
    if (!has_format) throw InvalidInput(fmt::format("{}: the PLY header has no format", source));

    Surface s;
    Body body(bytes.substr(at), format, source);
    bool has_vertices = false;
    std::vector<std::uint32_t> corners;
    for (const Element& e : elements) {
        const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
        int xyz[3] = {-1, -1, -1};
        for (std::size_t k = 0; k < e.properties.size(); ++k) {
            const Property& p = e.properties[k];
            for (int axis = 0; axis < 3; ++axis)
                if (!p.is_list && p.name == std::string(1, static_cast<char>('x' + axis)))
                    xyz[axis] = static_cast<int>(k);
        }
        if (is_vertex && (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0))
            throw InvalidInput(fmt::format("{}: element vertex lacks x, y or z", source));
        if (is_vertex) has_vertices = true;
        for (std::uint64_t item = 0; item < e.count; ++item) {
            const std::string where = fmt::format("element {} {}", e.name, item);
            double position[3] = {0, 0, 0};
            for (std::size_t k = 0; k < e.properties.size(); ++k) {
                const Property& p = e.properties[k];
                if (!p.is_list) {
                    const double v = body.next(p.type, where);
                    for (int axis = 0; axis < 3; ++axis)
                        if (static_cast<int>(k) == xyz[axis]) position[axis] = v;
                    continue;
                }
                const double n = body.next(p.count_type, where);
                if (n < 0 || n > 1e6)
                    throw InvalidInput(fmt::format("{}: {}: a list of {} items", source, where, n));
                const bool corners_list =
                    is_face && (p.name == "vertex_indices" || p.name == "vertex_index");
                corners.clear();
                for (int i = 0; i < static_cast<int>(n); ++i) {
                    const double v = body.next(p.type, where);
                    if (!corners_list) continue;
                    if (!(v >= 0 && v < 4294967295.0) || v != std::floor(v)) {
                        throw InvalidInput(fmt::format("{}: {}: vertex index {} is out of range",
                                                       source, where, v));
                    }
                    corners.push_back(static_cast<std::uint32_t>(v));
                }
                if (!corners_list) continue;
                if (corners.size() < 3) {
                    throw InvalidInput(
                        fmt::format("{}: {}: a face needs at least 3 corners, got {}", source,
                                    where, corners.size()));
                }
                for (std::size_t c = 1; c + 1 < corners.size(); ++c)
                    s.triangles.push_back({corners[0], corners[c], corners[c + 1]});
            }
            if (is_vertex) {
                const Vec3 v{position[0], position[1], position[2]};
                if (!is_finite(v)) {
                    throw InvalidInput(
                        fmt::format("{}: {} has a non-finite coordinate", source, where));
                }
                s.vertices.push_back(v);
            }
        }
    }
    if (!has_vertices) throw InvalidInput(fmt::format("{}: no vertex element", source));
    if (s.triangles.empty()) throw InvalidInput(fmt::format("{}: no faces", source));
    for (std::size_t t = 0; t < s.size(); ++t) {
        for (const std::uint32_t v : s.triangles[t]) {
            if (v >= s.vertices.size()) {
                throw InvalidInput(fmt::format("{}: a face refers to vertex {}, but there are {}",
                                               source, v, s.vertices.size()));
            }
        }
    }
    return s;
}

}  // namespace slc
