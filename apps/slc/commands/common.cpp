// Shared command-line pieces: interface loading, domain resolution, defaults.
#include "commands/common.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/geometry/validate.hpp"
#include "slc/io/interface_json.hpp"

namespace slc::cli {

void add_domain_options(CLI::App& cmd, DomainOptions& options) {
    auto* domain =
        cmd.add_option("--domain", options.half_width,
                       "Half-width b of the square domain [-b, b]^2 (default: the square "
                       "around the curves' bounding box, 1.5 times its larger half-side)");
    auto* box = cmd.add_option("--box", options.box, "The square domain as x0,y0,x1,y1");
    domain->excludes(box);
}

namespace {

Box parse_box(const std::string& text) {
    std::vector<double> v;
    std::stringstream in(text);
    std::string field;
    while (std::getline(in, field, ',')) {
        try {
            std::size_t used = 0;
            v.push_back(std::stod(field, &used));
            if (used != field.size()) throw std::invalid_argument(field);
        } catch (const std::exception&) {
            throw InvalidInput(
                fmt::format("--box must be four numbers x0,y0,x1,y1, got '{}'", text));
        }
    }
    if (v.size() != 4)
        throw InvalidInput(fmt::format("--box must be four numbers x0,y0,x1,y1, got '{}'", text));
    const Box b{{v[0], v[1]}, {v[2], v[3]}};
    if (!is_finite(b.lo) || !is_finite(b.hi) || !(b.width() > 0) || !(b.height() > 0)) {
        throw InvalidInput(
            fmt::format("--box must have x0 < x1 and y0 < y1, all finite, got '{}'", text));
    }
    if (std::abs(b.width() - b.height()) > 1e-12 * b.width()) {
        throw InvalidInput(
            fmt::format("--box must be a square, got {} wide and {} high", b.width(), b.height()));
    }
    return {b.lo, {b.hi.x, b.lo.y + b.width()}};
}

}  // namespace

Box resolve_domain(const DomainOptions& options, const std::vector<std::vector<Vec2>>& raw) {
    if (options.half_width) {
        const double b = *options.half_width;
        if (!(b > 0.0) || !std::isfinite(b)) {
            throw InvalidInput(fmt::format("--domain must be a positive half-width, got {}", b));
        }
        return Box::centered_square(b);
    }
    if (options.box) return parse_box(*options.box);
    Box bounds = Box::empty();  // of the finite points: the others are reported by validation
    for (const auto& curve : raw) bounds = unite(bounds, bounding_box(curve));
    if (bounds.is_empty()) throw InvalidInput("no curves: the interface is empty");
    const double half = 1.5 * std::max({0.5 * bounds.width(), 0.5 * bounds.height(), 1e-300});
    return Box::square(bounds.center(), half);
}

LoadedInterface load_interface(const std::string& path, const DomainOptions& domain) {
    InterfaceFile file = read_interface_json(path);
    const Box box = resolve_domain(domain, file.curves);
    PreparedInterface prepared = prepare_interface(file.curves, box);
    for (const std::string& note : prepared.notes) fmt::print(stderr, "slc: {}: {}\n", path, note);
    return {std::move(prepared.curves), file.time, box};
}

int default_tree_depth(const Interface& curves, const Box& domain) {
    const double mean = length(curves) / static_cast<double>(curves.size());
    const int level =
        static_cast<int>(std::ceil(std::log2(domain.width() / std::max(mean, 1e-300))));
    return std::clamp(level, 2, 16);
}

nlohmann::json box_json(const Box& b) { return {b.lo.x, b.lo.y, b.hi.x, b.hi.y}; }

void apply_threads(int threads) { set_thread_count(threads); }

}  // namespace slc::cli
