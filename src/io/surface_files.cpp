// Surface files: OBJ, STL (ASCII and binary) and PLY (ASCII and binary) readers, each checking
// the file's own structure and naming the line or record at fault; the OBJ writer.
#include "slc/io/surface_files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <unordered_map>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/io/interface_json.hpp"
#include "slc/io/vdb.hpp"

namespace slc {
namespace {

/// Lines of a text, numbered from 1, with CR and surrounding blanks removed.
class Lines {
public:
    explicit Lines(std::string_view text) : rest_(text) {}
    /// The next line, or false at the end.
    bool next(std::string_view& line) {
        if (rest_.empty()) return false;
        const std::size_t newline = rest_.find('\n');
        line = rest_.substr(0, newline);
        rest_ = newline == std::string_view::npos ? std::string_view{} : rest_.substr(newline + 1);
        ++number_;
        return true;
    }
    std::size_t number() const { return number_; }
    /// What follows the last line returned.
    std::string_view rest() const { return rest_; }

private:
    std::string_view rest_;
    std::size_t number_ = 0;
};

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

/// The blank-separated words of a line.
std::vector<std::string_view> words(std::string_view line) {
    std::vector<std::string_view> out;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && is_blank(line[i])) ++i;
        const std::size_t start = i;
        while (i < line.size() && !is_blank(line[i])) ++i;
        if (i > start) out.push_back(line.substr(start, i - start));
    }
    return out;
}

/// A word as it may appear in a one-line message: printable ASCII only, at most 24 characters.
std::string shown(std::string_view word) {
    std::string out;
    for (const char c : word.substr(0, 24)) {
        const auto byte = static_cast<unsigned char>(c);
        out += byte >= 0x20 && byte < 0x7f ? c : '?';
    }
    return word.size() > 24 ? out + "..." : out;
}

/// A finite number filling the whole word, or InvalidInput naming place.
double number(std::string_view word, const std::string& place) {
    std::string_view digits = word;
    if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-') digits.remove_prefix(1);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (ec != std::errc{} || end != digits.data() + digits.size() || !std::isfinite(value))
        throw InvalidInput(fmt::format("{}: \"{}\" is not a finite number", place, shown(word)));
    return value;
}

/// An integer filling the whole word, or InvalidInput naming place.
long long integer(std::string_view word, const std::string& place) {
    long long value = 0;
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (ec != std::errc{} || end != word.data() + word.size())
        throw InvalidInput(fmt::format("{}: \"{}\" is not an integer", place, shown(word)));
    return value;
}

/// Triangles fanned from the first corner of a polygon.
void fan(const std::vector<std::uint32_t>& corners, std::vector<TriangleIndices>& out) {
    for (std::size_t k = 1; k + 1 < corners.size(); ++k)
        out.push_back({corners[0], corners[k], corners[k + 1]});
}

/// Vertices merged by exactly equal coordinates (STL lists each corner in every triangle).
class VertexMerger {
public:
    std::uint32_t add(Vec3 p, std::vector<Vec3>& vertices) {
        p = p + Vec3{};  // −0 + 0 = +0: both zeros become one key
        const Key key{std::bit_cast<std::uint64_t>(p.x), std::bit_cast<std::uint64_t>(p.y),
                      std::bit_cast<std::uint64_t>(p.z)};
        auto [it, inserted] = index_.try_emplace(key, static_cast<std::uint32_t>(vertices.size()));
        if (inserted) vertices.push_back(p);
        return it->second;
    }

private:
    struct Key {
        std::uint64_t x, y, z;
        bool operator==(const Key&) const = default;
    };
    struct Hash {
        std::size_t operator()(const Key& k) const {
            std::uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
            h = (h ^ (h >> 29) ^ k.y) * 0xBF58476D1CE4E5B9ull;
            h = (h ^ (h >> 31) ^ k.z) * 0x94D049BB133111EBull;
            return static_cast<std::size_t>(h ^ (h >> 32));
        }
    };
    std::unordered_map<Key, std::uint32_t, Hash> index_;
};

Surface parse_stl_ascii(std::string_view text, const std::string& source) {
    Surface s;
    VertexMerger merger;
    Lines lines(text);
    std::string_view line;
    std::vector<std::uint32_t> loop;
    bool in_facet = false;
    bool seen_solid = false;
    while (lines.next(line)) {
        const auto w = words(line);
        if (w.empty()) continue;
        const std::string place = fmt::format("{}, line {}", source, lines.number());
        if (w[0] == "solid" || w[0] == "endsolid") {
            if (in_facet) throw InvalidInput(fmt::format("{}: {} inside a facet", place, w[0]));
            seen_solid = true;
        } else if (!seen_solid) {
            throw InvalidInput(fmt::format("{}: an ASCII STL file begins with \"solid\"", place));
        } else if (w[0] == "facet") {
            if (in_facet) throw InvalidInput(fmt::format("{}: facet inside a facet", place));
            in_facet = true;
            loop.clear();
        } else if (w[0] == "vertex") {
            if (!in_facet || w.size() != 4)
                throw InvalidInput(fmt::format("{}: expected \"vertex x y z\" in a facet", place));
            loop.push_back(merger.add(
                {number(w[1], place), number(w[2], place), number(w[3], place)}, s.vertices));
        } else if (w[0] == "endfacet") {
            if (!in_facet || loop.size() < 3) {
                throw InvalidInput(fmt::format("{}: a facet needs at least 3 vertices, got {}",
                                               place, loop.size()));
            }
            fan(loop, s.triangles);
            in_facet = false;
        } else if (w[0] != "outer" && w[0] != "endloop") {
            throw InvalidInput(fmt::format("{}: unexpected \"{}\"", place, shown(w[0])));
        }
    }
    if (in_facet) throw InvalidInput(fmt::format("{}: the file ends inside a facet", source));
    return s;
}

/// A little-endian 32-bit float at p.
float little_float(const char* p) {
    std::uint32_t u = 0;
    for (int i = 3; i >= 0; --i) u = (u << 8) | static_cast<unsigned char>(p[i]);
    return std::bit_cast<float>(u);
}

Surface parse_stl_binary(std::string_view bytes, const std::string& source) {
    std::uint32_t count = 0;
    for (int i = 3; i >= 0; --i) count = (count << 8) | static_cast<unsigned char>(bytes[80 + i]);
    Surface s;
    VertexMerger merger;
    s.triangles.reserve(count);
    for (std::uint32_t t = 0; t < count; ++t) {
        const char* record = bytes.data() + 84 + 50 * std::size_t{t};
        TriangleIndices tri{};
        for (int k = 0; k < 3; ++k) {
            const char* p = record + 12 + 12 * k;
            const Vec3 v{little_float(p), little_float(p + 4), little_float(p + 8)};
            if (!is_finite(v)) {
                throw InvalidInput(
                    fmt::format("{}: triangle {} has a non-finite coordinate", source, t));
            }
            tri[static_cast<std::size_t>(k)] = merger.add(v, s.vertices);
        }
        s.triangles.push_back(tri);
    }
    return s;
}

}  // namespace

bool is_surface_file(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".obj" || ext == ".stl" || ext == ".ply" || ext == ".vdb";
}

Surface parse_obj(std::string_view text, const std::string& source) {
    Surface s;
    std::vector<std::size_t> face_line;  // the line of each triangle, for indices checked last
    std::vector<std::uint32_t> corners;
    Lines lines(text);
    std::string_view line;
    while (lines.next(line)) {
        line = line.substr(0, line.find('#'));
        const auto w = words(line);
        if (w.empty()) continue;
        const std::string place = fmt::format("{}, line {}", source, lines.number());
        if (w[0] == "v") {
            if (w.size() < 4 || w.size() > 7) {
                throw InvalidInput(
                    fmt::format("{}: expected \"v x y z\", got {} numbers", place, w.size() - 1));
            }
            s.vertices.push_back({number(w[1], place), number(w[2], place), number(w[3], place)});
        } else if (w[0] == "f") {
            if (w.size() < 4) {
                throw InvalidInput(fmt::format("{}: a face needs at least 3 corners, got {}", place,
                                               w.size() - 1));
            }
            corners.clear();
            for (std::size_t k = 1; k < w.size(); ++k) {
                // "i", "i/t", "i//n" or "i/t/n": the vertex index comes first.
                const long long i = integer(w[k].substr(0, w[k].find('/')), place);
                const auto count = static_cast<long long>(s.vertices.size());
                // 1-based, or negative: −1 is the last vertex defined so far.
                const long long index = i < 0 ? count + i : i - 1;
                if (i == 0 || index < 0 || index > 0xfffffffell) {
                    throw InvalidInput(
                        fmt::format("{}: vertex index {} is out of range", place, shown(w[k])));
                }
                corners.push_back(static_cast<std::uint32_t>(index));
            }
            const std::size_t before = s.triangles.size();
            fan(corners, s.triangles);
            face_line.insert(face_line.end(), s.triangles.size() - before, lines.number());
        }
    }
    if (s.triangles.empty()) throw InvalidInput(fmt::format("{}: no faces", source));
    for (std::size_t t = 0; t < s.size(); ++t) {
        for (const std::uint32_t v : s.triangles[t]) {
            if (v >= s.vertices.size()) {
                throw InvalidInput(
                    fmt::format("{}, line {}: vertex index {} is out of range (there are {})",
                                source, face_line[t], v + 1, s.vertices.size()));
            }
        }
    }
    return s;
}

Surface parse_stl(std::string_view bytes, const std::string& source) {
    if (bytes.size() >= 84) {
        std::uint32_t count = 0;
        for (int i = 3; i >= 0; --i)
            count =
                (count << 8) | static_cast<unsigned char>(bytes[80 + static_cast<std::size_t>(i)]);
        const std::uint64_t expected = 84 + 50 * std::uint64_t{count};
        if (expected == bytes.size()) {
            Surface s = parse_stl_binary(bytes, source);
            if (s.empty()) throw InvalidInput(fmt::format("{}: no triangles", source));
            return s;
        }
        std::size_t first = 0;
        while (first < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[first])))
            ++first;
        if (bytes.substr(first, 5) != "solid") {
            throw InvalidInput(fmt::format(
                "{}: a binary STL file of {} triangles has {} bytes, but the file has {}", source,
                count, expected, bytes.size()));
        }
    }
    Surface s = parse_stl_ascii(bytes, source);
    if (s.empty()) throw InvalidInput(fmt::format("{}: no triangles", source));
    return s;
}

Surface read_surface(const std::filesystem::path& path) {
    if (!is_surface_file(path)) {
        throw InvalidInput(fmt::format(
            "{}: unknown surface format (expected .obj, .stl, .ply or .vdb)", path.string()));
    }
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".vdb") return read_vdb_level_set(path);
    const std::string bytes = read_text_file(path);
    if (ext == ".obj") return parse_obj(bytes, path.string());
    if (ext == ".stl") return parse_stl(bytes, path.string());
    return parse_ply(bytes, path.string());
}

std::string obj_text(const Surface& surface) {
    std::string out;
    out.reserve(60 * surface.vertices.size() + 30 * surface.size());
    for (const Vec3 p : surface.vertices)
        fmt::format_to(std::back_inserter(out), "v {} {} {}\n", p.x, p.y, p.z);
    for (const TriangleIndices& t : surface.triangles)
        fmt::format_to(std::back_inserter(out), "f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
    return out;
}

}  // namespace slc
