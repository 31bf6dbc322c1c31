// The history of slc run: history.csv kept in memory and written whole, read back on --resume,
// and its plot.
#include "commands/history.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <functional>
#include <string_view>
#include <system_error>

#include "slc/core/error.hpp"
#include "slc/io/interface_json.hpp"
#include "slc/io/plot.hpp"

namespace slc::cli {
namespace {

/// A field of a history line as a double; false unless the whole field is one.
bool parse_number(std::string_view field, double& value) {
    const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
    return ec == std::errc{} && end == field.data() + field.size();
}

/// t, area, length and components of a line of history.csv, its first four fields; false unless
/// the line is six numbers separated by commas.
bool parse_level(std::string_view line, double (&numbers)[4]) {
    std::size_t fields = 0;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = line.find(',', start);
        double value = 0.0;
        if (!parse_number(line.substr(start, comma - start), value)) return false;
        if (fields < 4) numbers[fields] = value;
        ++fields;
        if (comma == std::string_view::npos) return fields == 6;
        start = comma + 1;
    }
}

}  // namespace

History::History(std::filesystem::path dir)
    : dir_(std::move(dir)), csv_(fmt::format("{}\n", header)) {}

void History::record(double t, double area, double length, double components,
                     std::string_view line) {
    t_.push_back(t);
    area_.push_back(area);
    length_.push_back(length);
    components_.push_back(components);
    csv_ += line;
}

void History::start(double t, const Interface& curves) { add(t, curves, 0.0); }

void History::add(double t, const Interface& curves, double cpu_s) {
    const double a = area(curves);
    const double l = length(curves);
    // {} is the shortest form that reads back to the same double.
    record(t, a, l, static_cast<double>(curves.curve_count()),
           fmt::format("{},{},{},{},{},{}\n", t, a, l, curves.curve_count(), curves.size(), cpu_s));
}

void History::resume(int steps_done, double t, const std::filesystem::path& path) {
    const std::string text = read_text_file(path);
    auto fail = [&](const std::string& why) {
        return InvalidInput(
            fmt::format("{}: {}; cannot continue the run's history", path.string(), why));
    };
    const std::size_t levels = static_cast<std::size_t>(steps_done) + 1;
    std::size_t at = text.find('\n');
    if (at == std::string::npos || std::string_view(text).substr(0, at) != header)
        throw fail(fmt::format("the first line is not {}", header));
    ++at;
    while (t_.size() < levels) {
        const std::size_t end = text.find('\n', at);
        if (end == std::string::npos) {
            throw fail(
                fmt::format("the checkpoint after step {} needs {} time levels, the file has {}",
                            steps_done, levels, t_.size()));
        }
        double numbers[4];
        if (!parse_level(std::string_view(text).substr(at, end - at), numbers)) {
            throw fail(fmt::format("line {} is not six comma-separated numbers", t_.size() + 2));
        }
        record(numbers[0], numbers[1], numbers[2], numbers[3],
               std::string_view(text).substr(at, end + 1 - at));
        at = end + 1;
    }
    if (t_.back() != t) {
        throw fail(fmt::format("t = {} after step {}, but the checkpoint is at t = {}", t_.back(),
                               steps_done, t));
    }
}

void History::save_csv() const { write_file_atomic(csv_path(), csv_); }

void History::save_plot(const std::string& name) const {
    const bool counted = std::adjacent_find(components_.begin(), components_.end(),
                                            std::not_equal_to<>()) != components_.end();
    LinePlot plot{.title = fmt::format("{}: area{} length{}", name, counted ? "," : " and",
                                       counted ? " and curves" : ""),
                  .x_name = "t",
                  .panels = {}};
    plot.panels.push_back({"area", {{t_, area_, palette_color(0)}}});
    plot.panels.push_back({"length", {{t_, length_, palette_color(1)}}});
    // The number of curves when it changed (particles coarsening, bubbles merging).
    if (counted) plot.panels.push_back({"curves", {{t_, components_, palette_color(2)}}});
    slc::save_plot(plot, dir_ / "history.png");
}

}  // namespace slc::cli
