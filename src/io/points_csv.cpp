// Point files for `slc distance` (DESIGN §6): one "x,y" per line, an optional header "x,y", blank
// lines, CRLF line ends and spaces around the numbers allowed; everything else is an error that
// names the file and the line.
#include "slc/io/points_csv.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string_view>
#include <system_error>

#include "slc/core/error.hpp"
#include "slc/core/input_text.hpp"
#include "slc/core/tolerances.hpp"
#include "slc/io/interface_json.hpp"

namespace slc {
namespace {

/// The fields of a line between commas, each trimmed.
std::vector<std::string_view> split_fields(std::string_view line) {
    std::vector<std::string_view> fields;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = line.find(',', start);
        fields.push_back(trim(line.substr(start, comma - start)));
        if (comma == std::string_view::npos) return fields;
        start = comma + 1;
    }
}

/// "x,y" or "x,y,z" (either case) for `columns` 2 or 3.
bool is_header(const std::vector<std::string_view>& fields, std::size_t columns) {
    auto is = [](std::string_view f, char c) {
        return f.size() == 1 && (f[0] == c || f[0] == c - 'a' + 'A');
    };
    return fields.size() == columns && is(fields[0], 'x') && is(fields[1], 'y') &&
           (columns == 2 || is(fields[2], 'z'));
}

/// A field as it may appear in a one-line message, in double quotes (printable()).
std::string quoted(std::string_view field) { return fmt::format("\"{}\"", printable(field)); }

/// One coordinate: the whole field must be a finite number (an optional leading '+' allowed)
/// within ±tolerance::max_coordinate.
double parse_coordinate(std::string_view field, const char* name, const std::string& place) {
    std::string_view digits = field;
    if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-') digits.remove_prefix(1);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (ec == std::errc::result_out_of_range) {
        throw InvalidInput(
            fmt::format("{}: {} = {} is out of the range of a double", place, name, quoted(field)));
    }
    if (ec != std::errc{} || end != digits.data() + digits.size()) {
        throw InvalidInput(fmt::format("{}: {} = {} is not a number", place, name, quoted(field)));
    }
    if (!std::isfinite(value)) {
        throw InvalidInput(fmt::format("{}: {} = {} is not finite", place, name, quoted(field)));
    }
    if (std::abs(value) > tolerance::max_coordinate) {
        throw InvalidInput(fmt::format("{}: {} = {} is beyond the coordinate limit ±{:g}", place,
                                       name, quoted(field), tolerance::max_coordinate));
    }
    return value;
}

/// The coordinates of every point line, `columns` (2 or 3) to a point, one after another.
std::vector<double> parse_columns(const std::string& text, const std::string& source,
                                  std::size_t columns) {
    static constexpr const char* names[3] = {"x", "y", "z"};
    std::string_view rest = text;
    if (rest.starts_with("\xEF\xBB\xBF")) rest.remove_prefix(3);  // a UTF-8 byte-order mark
    std::vector<double> values;
    bool first_content = true;
    for (std::size_t line_number = 1; !rest.empty(); ++line_number) {
        const std::size_t newline = rest.find('\n');
        const std::string_view line = trim(rest.substr(0, newline));
        rest = newline == std::string_view::npos ? std::string_view{} : rest.substr(newline + 1);
        if (line.empty()) continue;

        const std::vector<std::string_view> fields = split_fields(line);
        const bool header = first_content && is_header(fields, columns);
        first_content = false;
        if (header) continue;
        const std::string place = fmt::format("{}, line {}", source, line_number);
        if (fields.size() != columns) {
            throw InvalidInput(fmt::format("{}: expected {} columns {}, got {}", place, columns,
                                           columns == 2 ? "x,y" : "x,y,z", fields.size()));
        }
        for (std::size_t i = 0; i < columns; ++i)
            values.push_back(parse_coordinate(fields[i], names[i], place));
    }
    return values;
}

}  // namespace

std::vector<Vec2> parse_points_csv(const std::string& text, const std::string& source) {
    const std::vector<double> v = parse_columns(text, source, 2);
    std::vector<Vec2> points(v.size() / 2);
    for (std::size_t i = 0; i < points.size(); ++i) points[i] = {v[2 * i], v[2 * i + 1]};
    return points;
}

std::vector<Vec3> parse_points3_csv(const std::string& text, const std::string& source) {
    const std::vector<double> v = parse_columns(text, source, 3);
    std::vector<Vec3> points(v.size() / 3);
    for (std::size_t i = 0; i < points.size(); ++i)
        points[i] = {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
    return points;
}

std::vector<Vec3> read_points3_csv(const std::filesystem::path& path) {
    return parse_points3_csv(read_text_file(path), path.string());
}

std::vector<Vec2> read_points_csv(const std::filesystem::path& path) {
    return parse_points_csv(read_text_file(path), path.string());
}

}  // namespace slc
