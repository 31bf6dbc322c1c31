// Regions of a documentation page that a benchmark program writes. A page is written by hand;
// what a program measures goes between a line `<!-- begin NAME -->` and a line
// `<!-- end NAME -->`, and the program replaces only that text. A page whose markers are missing,
// repeated or out of order is an error, reported before the program measures anything, so that
// neither a hand edit nor a two-hour run is lost silently.
#pragma once

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "slc/io/interface_json.hpp"

namespace slc::bench {

/// A region's name and the text a program writes into it.
using Region = std::pair<std::string, std::string>;

inline std::string region_begin(std::string_view name) {
    return "<!-- begin " + std::string(name) + " -->";
}
inline std::string region_end(std::string_view name) {
    return "<!-- end " + std::string(name) + " -->";
}

namespace detail {

/// Offsets of the lines of text that are exactly `line`, and of the line after each.
struct LineAt {
    std::size_t start = 0, next = 0;
};
inline std::vector<LineAt> lines_equal(std::string_view text, std::string_view line) {
    std::vector<LineAt> found;
    for (std::size_t start = 0; start < text.size();) {
        std::size_t eol = text.find('\n', start);
        if (eol == std::string_view::npos) eol = text.size();
        if (text.substr(start, eol - start) == line)
            found.push_back({start, std::min(eol + 1, text.size())});
        start = eol + 1;
    }
    return found;
}

/// Where the region's text lies: after its begin line, up to its end line. Empty message when
/// found, else why not.
struct Span {
    std::size_t first = 0, last = 0;
    std::string problem;
};
inline Span find_region(std::string_view text, std::string_view name) {
    const std::string b = region_begin(name), e = region_end(name);
    const auto begins = lines_equal(text, b), ends = lines_equal(text, e);
    if (begins.empty() || ends.empty()) return {0, 0, "lacks the line " + (begins.empty() ? b : e)};
    if (begins.size() > 1 || ends.size() > 1)
        return {0, 0, "has the line " + (begins.size() > 1 ? b : e) + " more than once"};
    if (ends[0].start < begins[0].next) return {0, 0, "has " + e + " before " + b};
    return {begins[0].next, ends[0].start, {}};
}

/// text without the newlines at its start and end.
inline std::string_view trimmed(std::string_view text) {
    while (!text.empty() && text.front() == '\n') text.remove_prefix(1);
    while (!text.empty() && text.back() == '\n') text.remove_suffix(1);
    return text;
}

/// Every problem of text's regions `names`, one a line, each prefixed by what; empty if none.
inline std::string problems(std::string_view text, const std::vector<std::string>& names,
                            const std::string& what) {
    std::string all;
    for (const std::string& name : names) {
        const Span s = find_region(text, name);
        if (s.problem.empty()) continue;
        if (!all.empty()) all += "\n";
        all += what + " " + s.problem;
    }
    return all;
}

}  // namespace detail

/// The text between the markers of region `name` of page, without the blank lines that
/// with_regions puts around it. Throws std::runtime_error when the markers are not usable.
inline std::string region_text(std::string_view page, std::string_view name) {
    const detail::Span s = detail::find_region(page, name);
    if (!s.problem.empty()) throw std::runtime_error("the page " + s.problem);
    return std::string(detail::trimmed(page.substr(s.first, s.last - s.first)));
}

/// page with each region's text replaced, a blank line on either side of it, the markers and
/// everything outside them kept. Throws std::runtime_error naming every region whose markers are
/// missing, repeated or out of order; then nothing is replaced.
inline std::string with_regions(std::string page, const std::vector<Region>& regions) {
    std::vector<std::string> names;
    for (const Region& r : regions) names.push_back(r.first);
    if (const std::string p = detail::problems(page, names, "the page"); !p.empty())
        throw std::runtime_error(p);
    for (const auto& [name, text] : regions) {
        const detail::Span s = detail::find_region(page, name);
        const std::string_view t = detail::trimmed(text);
        std::string block = "\n";
        if (!t.empty()) block.append(t).append("\n\n");
        page.replace(s.first, s.last - s.first, block);
    }
    return page;
}

/// Throws std::runtime_error, naming the page and every region at fault, unless the page at
/// path exists and holds the markers of every region in `names` once, in order. A program calls
/// it before it measures anything.
inline void require_regions(const std::filesystem::path& path,
                            const std::vector<std::string>& names) {
    if (!std::filesystem::exists(path))
        throw std::runtime_error(path.string() + " does not exist: it holds the regions " +
                                 "a benchmark writes, between markers, in a page written by hand");
    const std::string p = detail::problems(read_text_file(path), names, path.string());
    if (!p.empty()) throw std::runtime_error(p);
}

/// Replaces the regions of the page at path and writes it back atomically; throws, writing
/// nothing, as require_regions and with_regions do.
inline void write_regions(const std::filesystem::path& path, const std::vector<Region>& regions) {
    std::vector<std::string> names;
    for (const Region& r : regions) names.push_back(r.first);
    require_regions(path, names);
    write_file_atomic(path, with_regions(read_text_file(path), regions));
}

/// Checks the page at path as a program about to write `names` would, then writes every region
/// back with its own text and requires the page unchanged, so that a page's layout around its
/// markers survives a run. Throws std::runtime_error otherwise.
inline void check_regions(const std::filesystem::path& path,
                          const std::vector<std::string>& names) {
    require_regions(path, names);
    const std::string page = read_text_file(path);
    std::vector<Region> same;
    for (const std::string& name : names) same.emplace_back(name, region_text(page, name));
    if (with_regions(page, same) != page)
        throw std::runtime_error(path.string() +
                                 ": writing the regions back with their own text changes the "
                                 "page; each region's text wants one blank line on either side");
}

}  // namespace slc::bench
