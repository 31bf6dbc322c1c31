// The animated SVG of a run's frames, written as text: each frame a group whose visibility a
// discrete SMIL <animate> switches on for its slot of the loop (SVG 1.1, "Animation").
#include "slc/io/animation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/io/render.hpp"

namespace slc {
namespace {

// The page: a 560 px square plot, 20 px margins, room for the title above and the time below.
constexpr double plot_size = 560.0;
constexpr double margin = 20.0;
constexpr double plot_top = 44.0;
constexpr double page_width = plot_size + 2 * margin;
constexpr double page_height = plot_top + plot_size + 36.0;

std::string xml_escape(const std::string& text) {
    std::string out;
    for (const char c : text) {
        switch (c) {
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '&':
                out += "&amp;";
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

std::string css(Color c) {
    auto byte = [](double v) {
        return static_cast<int>(std::lround(255.0 * std::clamp(v, 0.0, 1.0)));
    };
    return fmt::format("#{:02x}{:02x}{:02x}", byte(c.r), byte(c.g), byte(c.b));
}

/// Maps the plane's square view onto the plot, y upward.
struct PageMap {
    Box view;
    Vec2 operator()(Vec2 p) const {
        return {margin + (p.x - view.lo.x) / view.width() * plot_size,
                plot_top + (view.hi.y - p.y) / view.height() * plot_size};
    }
};

/// Every curve as a closed subpath, to 0.01 px.
std::string path_data(const Interface& curves, const PageMap& map) {
    std::string d;
    for (std::size_t c = 0; c < curves.curve_count(); ++c) {
        const auto curve = curves.curve(c);
        for (std::size_t i = 0; i < curve.size(); ++i) {
            const Vec2 q = map(curve[i]);
            fmt::format_to(std::back_inserter(d), "{}{:.2f} {:.2f}", i == 0 ? "M" : "L", q.x, q.y);
        }
        d += "Z";
    }
    return d;
}

Box square_view(const Box& view) {
    const double w = view.width();
    const double h = view.height();
    if (!std::isfinite(w) || !std::isfinite(h) || !(std::max(w, h) > 0.0) || w < 0.0 || h < 0.0) {
        throw InvalidInput(fmt::format("animation view box [{}, {}] x [{}, {}] is empty", view.lo.x,
                                       view.hi.x, view.lo.y, view.hi.y));
    }
    return Box::square(view.center(), 0.5 * std::max(w, h));
}

}  // namespace

std::string animated_svg(std::span<const AnimationFrame> frames, const Box& view,
                         const AnimationOptions& options) {
    if (frames.empty()) throw InvalidInput("an animation needs at least one frame");
    if (!(options.seconds_per_frame > 0.0) || !std::isfinite(options.seconds_per_frame)) {
        throw InvalidInput(
            fmt::format("seconds per frame must be positive, got {}", options.seconds_per_frame));
    }
    for (const AnimationFrame& f : frames) {
        if (!std::isfinite(f.time))
            throw InvalidInput(fmt::format("animation frame time must be finite, got {}", f.time));
    }
    const PageMap map{square_view(view)};
    const std::size_t n = frames.size();
    const double loop_s = options.seconds_per_frame * static_cast<double>(n);
    auto along = [n](std::size_t i) {
        return n < 2 ? 0.0 : static_cast<double>(i) / static_cast<double>(n - 1);
    };

    std::string out;
    fmt::format_to(std::back_inserter(out),
                   "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                   "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" "
                   "viewBox=\"0 0 {0} {1}\" font-family=\"sans-serif\">\n"
                   "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
                   page_width, page_height);
    if (!options.title.empty()) {
        fmt::format_to(
            std::back_inserter(out),
            "<text x=\"{}\" y=\"28\" font-size=\"17\" text-anchor=\"middle\">{}</text>\n",
            page_width / 2, xml_escape(options.title));
    }
    fmt::format_to(std::back_inserter(out),
                   "<rect x=\"{0}\" y=\"{1}\" width=\"{2}\" height=\"{2}\" fill=\"none\" "
                   "stroke=\"black\"/>\n",
                   margin, plot_top, plot_size);
    fmt::format_to(std::back_inserter(out),
                   "<text x=\"{}\" y=\"{}\" font-size=\"12\" fill=\"#555\">[{:.4g}, {:.4g}] x "
                   "[{:.4g}, {:.4g}]</text>\n",
                   margin, plot_top + plot_size + 16, map.view.lo.x, map.view.hi.x, map.view.lo.y,
                   map.view.hi.y);
    // Each frame's colour and path, written once and used by the trail and by the frame.
    std::vector<std::string> colour(n), path(n);
    for (std::size_t i = 0; i < n; ++i) {
        if (frames[i].curves.empty()) continue;
        colour[i] = css(sequence_color(along(i)));
        path[i] = path_data(frames[i].curves, map);
    }
    if (options.trail) {
        out += "<g id=\"trail\" fill=\"none\" stroke-width=\"0.8\" stroke-opacity=\"0.6\">\n";
        for (std::size_t i = 0; i < n; ++i) {
            if (frames[i].curves.empty()) continue;
            fmt::format_to(std::back_inserter(out), "<path stroke=\"{}\" d=\"{}\"/>\n", colour[i],
                           path[i]);
        }
        out += "</g>\n";
    }
    // Frame i shows during [i/n, (i+1)/n) of the loop: a discrete animation holds each value from
    // its key time to the next.
    for (std::size_t i = 0; i < n; ++i) {
        const double on = static_cast<double>(i) / static_cast<double>(n);
        const double off = static_cast<double>(i + 1) / static_cast<double>(n);
        const std::string values = i == 0 ? "visible;hidden" : "hidden;visible;hidden";
        const std::string key_times =
            i == 0 ? fmt::format("0;{}", off) : fmt::format("0;{};{}", on, off);
        fmt::format_to(std::back_inserter(out), "<g id=\"frame{}\" visibility=\"hidden\">\n", i);
        if (!frames[i].curves.empty()) {
            fmt::format_to(std::back_inserter(out),
                           "<path fill=\"{0}\" fill-opacity=\"0.25\" fill-rule=\"evenodd\" "
                           "stroke=\"{0}\" stroke-width=\"2\" d=\"{1}\"/>\n",
                           colour[i], path[i]);
        }
        fmt::format_to(std::back_inserter(out),
                       "<text x=\"{}\" y=\"{}\" font-size=\"14\" text-anchor=\"end\">t = {:.4g}"
                       "{}</text>\n",
                       margin + plot_size, plot_top + plot_size + 18, frames[i].time,
                       frames[i].curves.empty() ? " (nothing left)" : "");
        fmt::format_to(std::back_inserter(out),
                       "<animate attributeName=\"visibility\" calcMode=\"discrete\" values=\"{}\" "
                       "keyTimes=\"{}\" dur=\"{}s\" repeatCount=\"indefinite\"/>\n</g>\n",
                       values, key_times, loop_s);
    }
    out += "</svg>\n";
    return out;
}

}  // namespace slc
