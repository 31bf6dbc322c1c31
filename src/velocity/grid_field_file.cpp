// The files of a lattice velocity (slc run --field-file): CSV lines x,y,u,v in any order, and
// legacy VTK STRUCTURED_POINTS in ASCII with a vector point-data array.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>
#include <system_error>

#include "slc/core/error.hpp"
#include "slc/core/input_text.hpp"
#include "slc/velocity/grid_field.hpp"

namespace slc {
namespace {

/// Distinct coordinates that differ by less than this fraction of the spacing are one lattice
/// line, and each must lie this close to its lattice position: the check is against lattices that
/// are not uniform, not against coordinates rounded when printed.
constexpr double lattice_tolerance = 1e-3;

/// A field shown in a one-line message, in single quotes (printable()).
std::string quoted(std::string_view field) { return fmt::format("'{}'", printable(field)); }

/// The number the whole of field spells (a leading '+' allowed), if any.
std::optional<double> number(std::string_view field) {
    if (field.size() > 1 && field[0] == '+' && field[1] != '-') field.remove_prefix(1);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
    if (ec != std::errc{} || end != field.data() + field.size()) return std::nullopt;
    return value;
}

/// One axis of a lattice from the coordinates of its points: origin, spacing and count, and each
/// coordinate's index.
struct LatticeAxis {
    double origin = 0.0;
    double spacing = 0.0;
    std::size_t count = 0;
    std::size_t index(double c) const {
        return static_cast<std::size_t>(std::llround((c - origin) / spacing));
    }
};

LatticeAxis lattice_axis(std::vector<double> c, const char* name, const std::string& source) {
    std::sort(c.begin(), c.end());
    const double range = c.back() - c.front();
    // Distinct values: a gap of more than a thousandth of the smallest conceivable spacing (the
    // range over the number of points) starts a new one.
    const double merge = lattice_tolerance * range / static_cast<double>(c.size());
    std::vector<double> distinct = {c.front()};
    for (const double v : c)
        if (v - distinct.back() > merge) distinct.push_back(v);
    if (distinct.size() < 2) {
        throw InvalidInput(
            fmt::format("{}: the lattice needs at least 2 distinct {} values, got {}", source, name,
                        distinct.size()));
    }
    LatticeAxis a{c.front(), range / static_cast<double>(distinct.size() - 1), distinct.size()};
    for (std::size_t k = 0; k < distinct.size(); ++k) {
        const double expected = a.origin + static_cast<double>(k) * a.spacing;
        if (std::abs(distinct[k] - expected) > lattice_tolerance * a.spacing) {
            throw InvalidInput(fmt::format(
                "{}: the {} values are not evenly spaced: {} where the lattice of spacing {} has "
                "{}",
                source, name, distinct[k], a.spacing, expected));
        }
    }
    return a;
}

/// The whitespace-separated words of a VTK file after its three header lines.
class Words {
public:
    Words(std::string_view text, std::string source) : rest_(text), source_(std::move(source)) {}

    bool empty() {
        skip_blanks();
        return rest_.empty();
    }
    std::string_view next(const char* what) {
        skip_blanks();
        if (rest_.empty())
            throw InvalidInput(
                fmt::format("{}: the file ends where {} was expected", source_, what));
        const std::size_t end = std::min(rest_.find_first_of(" \t\r\n\f\v"), rest_.size());
        const std::string_view word = rest_.substr(0, end);
        rest_.remove_prefix(end);
        return word;
    }
    double real(const char* what) {
        const std::string_view w = next(what);
        const std::optional<double> v = number(w);
        if (!v) throw fail(fmt::format("{} {} is not a number", what, quoted(w)));
        return *v;
    }
    std::size_t count(const char* what) {
        const double v = real(what);
        if (!(v >= 0.0) || v != std::floor(v) || v > 1e12)
            throw fail(fmt::format("{} must be a whole number, got {}", what, v));
        return static_cast<std::size_t>(v);
    }
    /// The rest of the current line, consumed (the optional last word of a SCALARS line).
    std::string_view line() {
        const std::size_t end = rest_.find('\n');
        const std::string_view l = rest_.substr(0, end);
        rest_.remove_prefix(end == std::string_view::npos ? rest_.size() : end + 1);
        return l;
    }
    InvalidInput fail(const std::string& why) const {
        return InvalidInput(fmt::format("{}: {}", source_, why));
    }

private:
    void skip_blanks() {
        const std::size_t first = rest_.find_first_not_of(" \t\r\n\f\v");
        rest_.remove_prefix(first == std::string_view::npos ? rest_.size() : first);
    }
    std::string_view rest_;
    std::string source_;
};

/// The header of a STRUCTURED_POINTS dataset, up to POINT_DATA.
struct VtkLattice {
    std::size_t dims[3] = {0, 0, 0};
    double origin[3] = {0, 0, 0};
    double spacing[3] = {1, 1, 1};
};

VtkLattice read_vtk_lattice(Words& w) {
    if (w.next("DATASET") != "DATASET") throw w.fail("expected DATASET after the header");
    const std::string_view kind = w.next("the dataset type");
    if (kind != "STRUCTURED_POINTS") {
        throw w.fail(
            fmt::format("dataset {} is not read; a velocity lattice is DATASET STRUCTURED_POINTS",
                        quoted(kind)));
    }
    VtkLattice l;
    for (std::string_view word = w.next("POINT_DATA"); word != "POINT_DATA";
         word = w.next("POINT_DATA")) {
        if (word == "DIMENSIONS") {
            for (auto& d : l.dims) d = w.count("DIMENSIONS");
        } else if (word == "ORIGIN") {
            for (auto& o : l.origin) o = w.real("ORIGIN");
        } else if (word == "SPACING" || word == "ASPECT_RATIO") {
            for (auto& s : l.spacing) s = w.real("SPACING");
        } else {
            throw w.fail(fmt::format("unexpected {} before POINT_DATA", quoted(word)));
        }
    }
    if (l.dims[2] != 1) {
        throw w.fail(
            fmt::format("the lattice must be 2D (DIMENSIONS nx ny 1), got nz = {}", l.dims[2]));
    }
    return l;
}

/// Reads `values` numbers, or skips them when out is null.
void read_values(Words& w, std::size_t values, std::vector<double>* out) {
    if (out) out->reserve(values);
    for (std::size_t k = 0; k < values; ++k) {
        const double v = w.real("a data value");
        if (out) out->push_back(v);
    }
}

}  // namespace

GridVelocity parse_grid_csv(std::string_view text, const std::string& source) {
    if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);  // a UTF-8 byte-order mark
    std::vector<double> xs, ys;
    std::vector<Vec2> us;
    std::vector<std::size_t> lines;
    bool first_content = true;
    for (std::size_t line_number = 1; !text.empty(); ++line_number) {
        const std::size_t newline = text.find('\n');
        const std::string_view line = trim(text.substr(0, newline));
        text = newline == std::string_view::npos ? std::string_view{} : text.substr(newline + 1);
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::optional<double>> fields;
        for (std::size_t start = 0;;) {
            const std::size_t comma = line.find(',', start);
            fields.push_back(number(trim(line.substr(start, comma - start))));
            if (comma == std::string_view::npos) break;
            start = comma + 1;
        }
        const bool numbers =
            fields.size() == 4 &&
            std::all_of(fields.begin(), fields.end(), [](auto f) { return f.has_value(); });
        if (!numbers && first_content) {  // a header
            first_content = false;
            continue;
        }
        first_content = false;
        if (!numbers) {
            throw InvalidInput(fmt::format("{}, line {}: expected 4 numbers x,y,u,v, got {}",
                                           source, line_number, quoted(line)));
        }
        for (const auto& f : fields) {
            if (!std::isfinite(*f)) {
                throw InvalidInput(fmt::format("{}, line {}: a value is not finite: {}", source,
                                               line_number, quoted(line)));
            }
        }
        xs.push_back(*fields[0]);
        ys.push_back(*fields[1]);
        us.push_back({*fields[2], *fields[3]});
        lines.push_back(line_number);
    }
    if (us.empty()) throw InvalidInput(fmt::format("{}: no lines x,y,u,v", source));
    const LatticeAxis ax = lattice_axis(xs, "x", source), ay = lattice_axis(ys, "y", source);
    if (us.size() != ax.count * ay.count) {
        throw InvalidInput(fmt::format(
            "{}: {} lines for a lattice of {} x {} points; each point needs exactly one line",
            source, us.size(), ax.count, ay.count));
    }
    GridVelocity g{{ax.origin, ay.origin}, {ax.spacing, ay.spacing}, ax.count, ay.count, {}};
    g.values.resize(us.size());
    std::vector<char> seen(us.size(), 0);
    for (std::size_t k = 0; k < us.size(); ++k) {
        const std::size_t at = ax.index(xs[k]) + ax.count * ay.index(ys[k]);
        if (seen[at]) {
            throw InvalidInput(fmt::format("{}, line {}: the point ({}, {}) appears twice", source,
                                           lines[k], xs[k], ys[k]));
        }
        seen[at] = 1;
        g.values[at] = us[k];
    }
    return g;
}

GridVelocity parse_grid_vtk(std::string_view text, const std::string& source) {
    auto header_line = [&text]() {
        const std::size_t newline = text.find('\n');
        const std::string_view line = trim(text.substr(0, newline));
        text = newline == std::string_view::npos ? std::string_view{} : text.substr(newline + 1);
        return line;
    };
    if (!header_line().starts_with("# vtk DataFile"))
        throw InvalidInput(
            fmt::format("{}: not a legacy VTK file (no '# vtk DataFile' line)", source));
    header_line();  // the title
    const std::string_view format = header_line();
    if (format != "ASCII") {
        throw InvalidInput(fmt::format("{}: only ASCII legacy VTK files are read, this one is {}",
                                       source, quoted(format)));
    }
    Words w(text, source);
    const VtkLattice l = read_vtk_lattice(w);
    const std::size_t n = w.count("POINT_DATA");
    if (n != l.dims[0] * l.dims[1]) {
        throw w.fail(
            fmt::format("POINT_DATA {} for a lattice of {} x {} points", n, l.dims[0], l.dims[1]));
    }
    // The attributes: the first with 2 or 3 components is the velocity; the others are skipped.
    std::vector<double> data;
    std::size_t components = 0;
    while (components == 0 && !w.empty()) {
        const std::string_view word = w.next("an attribute");
        std::size_t comps = 0;  // of this attribute
        std::size_t tuples = n;
        if (word == "VECTORS" || word == "NORMALS") {
            w.next("a name");
            w.next("a type");
            comps = 3;
        } else if (word == "SCALARS") {
            w.next("a name");
            w.next("a type");
            const std::string_view rest = trim(w.line());  // numComp, 1 when not given
            comps = 1;
            if (!rest.empty()) {
                const std::optional<double> c = number(rest);
                if (!c || !(*c >= 1.0 && *c <= 4.0) || *c != std::floor(*c))
                    throw w.fail(fmt::format("SCALARS with {} components", quoted(rest)));
                comps = static_cast<std::size_t>(*c);
            }
            if (w.next("LOOKUP_TABLE") != "LOOKUP_TABLE")
                throw w.fail("expected LOOKUP_TABLE after SCALARS");
            w.next("a lookup table name");
        } else if (word == "LOOKUP_TABLE") {  // a table of colours: name, size, RGBA each
            w.next("a name");
            read_values(w, 4 * w.count("the table size"), nullptr);
            continue;
        } else if (word == "FIELD") {
            w.next("a name");
            const std::size_t arrays = w.count("the number of arrays");
            for (std::size_t a = 0; a < arrays && components == 0; ++a) {
                w.next("an array name");
                const std::size_t c = w.count("the number of components");
                const std::size_t t = w.count("the number of tuples");
                w.next("a type");
                const bool velocity = (c == 2 || c == 3) && t == n;
                read_values(w, c * t, velocity ? &data : nullptr);
                if (velocity) components = c;
            }
            continue;
        } else if (word == "CELL_DATA") {
            break;
        } else {
            throw w.fail(fmt::format("attribute {} is not read (VECTORS, SCALARS and FIELD are)",
                                     quoted(word)));
        }
        const bool velocity = comps == 2 || comps == 3;
        read_values(w, comps * tuples, velocity ? &data : nullptr);
        if (velocity) components = comps;
    }
    if (components == 0) {
        throw w.fail(
            "no point-data array with 2 or 3 components (VECTORS, or SCALARS or FIELD "
            "with 2 or 3) to take the velocity from");
    }
    GridVelocity g{
        {l.origin[0], l.origin[1]}, {l.spacing[0], l.spacing[1]}, l.dims[0], l.dims[1], {}};
    g.values.resize(n);
    for (std::size_t k = 0; k < n; ++k)
        g.values[k] = {data[components * k], data[components * k + 1]};
    return g;
}

GridVelocity read_grid_velocity(const std::filesystem::path& path) {
    const std::string text = file_bytes(path);
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".vtk" ? parse_grid_vtk(text, path.string())
                         : parse_grid_csv(text, path.string());
}

}  // namespace slc
