// Line plots: panels stacked over one shared x axis, each panel's y axis scaled to its own data,
// with the ticks, text and output of the picture module (render_layout.hpp).
#include "slc/io/plot.hpp"

#include <cairo.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "render_layout.hpp"
#include "slc/core/error.hpp"

namespace slc {
namespace {

using namespace render_detail;

// Page layout in layout pixels, beside render_layout.hpp's margins and fonts: a panel is as wide
// as a Figure's plot and a little under half as high, so that two of them make a page of about
// the same size.
constexpr double panel_height = 240.0;
constexpr double panel_gap = 16.0;  // between stacked panels: room for the upper one's x ticks
// The y axis spans its data with this margin on each side, as a fraction of the data's range ...
constexpr double y_margin = 0.05;
// ... and at least this fraction of the largest magnitude: ticks finer than that would need more
// digits than their labels show (render's nice_ticks prints 6 significant digits in scientific
// form), and a drift of less than 0.1% is best drawn flat.
constexpr double min_relative_span = 1e-3;
const Color grid_color{0.88, 0.88, 0.88, 1.0};

struct Range {
    double lo = 0.0;
    double hi = 1.0;
};

/// [lo, hi] grown by `margin` of its span on each side, then widened about its centre to at least
/// min_relative_span of its largest magnitude (to [−1, 1] around 0).
Range axis_range(double lo, double hi, double margin) {
    const double pad = margin * (hi - lo);
    lo -= pad;
    hi += pad;
    const double least = min_relative_span * std::max(std::abs(lo), std::abs(hi));
    if (hi - lo < least) {
        const double c = 0.5 * (lo + hi);
        lo = c - 0.5 * least;
        hi = c + 0.5 * least;
    }
    if (!(hi > lo)) return {lo - 1.0, hi + 1.0};  // every value 0
    return {lo, hi};
}

/// The range of values over every series (xs: abscissae, else ordinates); [0, 1] when empty.
Range data_range(const std::vector<const PlotSeries*>& series, bool xs, double margin) {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (const PlotSeries* s : series) {
        for (const double v : xs ? s->x : s->y) lo = std::min(lo, v), hi = std::max(hi, v);
    }
    if (lo > hi) return {};
    return axis_range(lo, hi, margin);
}

void check(const LinePlot& plot) {
    if (plot.panels.empty()) throw InvalidInput("a line plot needs at least one panel");
    for (std::size_t p = 0; p < plot.panels.size(); ++p) {
        const std::vector<PlotSeries>& series = plot.panels[p].series;
        for (std::size_t i = 0; i < series.size(); ++i) {
            const PlotSeries& s = series[i];
            const std::string name =
                fmt::format("plot panel {} ({}), series {}", p, plot.panels[p].y_name, i);
            if (s.x.size() != s.y.size()) {
                throw InvalidInput(
                    fmt::format("{}: {} x values but {} y values", name, s.x.size(), s.y.size()));
            }
            for (std::size_t j = 0; j < s.x.size(); ++j) {
                if (!std::isfinite(s.x[j]) || !std::isfinite(s.y[j])) {
                    throw InvalidInput(fmt::format("{}: point {} ({}, {}) is not finite", name, j,
                                                   s.x[j], s.y[j]));
                }
            }
            if (!(s.line_width > 0.0) || !std::isfinite(s.line_width)) {
                throw InvalidInput(fmt::format("{}: line width must be positive and finite, got {}",
                                               name, s.line_width));
            }
        }
    }
}

/// One panel on the page: its data ranges, ticks and where it sits.
struct PanelPage {
    const PlotPanel* panel = nullptr;
    Range x;
    Range y;
    Ticks y_ticks;
    double top = 0.0;

    double page_x(double left, double v) const {
        return left + (v - x.lo) / (x.hi - x.lo) * plot_size;
    }
    double page_y(double v) const { return top + (y.hi - v) / (y.hi - y.lo) * panel_height; }
};

/// Where everything goes on the page.
struct PlotPage {
    double width = 0.0;
    double height = 0.0;
    double left = 0.0;      // the panels' left edge
    double y_name_x = 0.0;  // centre of the turned y axis names
    Ticks x_ticks;
    std::vector<PanelPage> panels;
};

PlotPage plot_layout(const LinePlot& plot) {
    PlotPage page;
    std::vector<const PlotSeries*> all;
    for (const PlotPanel& panel : plot.panels)
        for (const PlotSeries& s : panel.series) all.push_back(&s);
    const Range x = data_range(all, true, 0.0);
    page.x_ticks = nice_ticks(x.lo, x.hi);

    const SurfacePtr scratch(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1),
                             &cairo_surface_destroy);
    const ContextPtr cr(cairo_create(scratch.get()), &cairo_destroy);
    set_font(cr.get(), font_size);
    double widest = 0.0;  // y tick label, over every panel, so that the panels line up
    double top = top_margin + (plot.title.empty() ? 0.0 : title_room);
    for (const PlotPanel& panel : plot.panels) {
        std::vector<const PlotSeries*> series;
        for (const PlotSeries& s : panel.series) series.push_back(&s);
        PanelPage p{&panel, x, data_range(series, false, y_margin), {}, top};
        p.y_ticks = nice_ticks(p.y.lo, p.y.hi);
        for (const std::string& s : p.y_ticks.labels)
            widest = std::max(widest, text_width(cr.get(), s));
        page.panels.push_back(std::move(p));
        top += panel_height + panel_gap;
    }
    // As render's layout: tick, gap, widest label, gap, the axis name (about one em), margin.
    page.left = std::max(min_left_margin, tick_length + label_gap + widest + 2.5 * font_size + 8.0);
    page.y_name_x = page.left - tick_length - label_gap - widest - font_size;
    page.width = std::ceil(page.left + plot_size + right_margin);
    page.height = std::ceil(top - panel_gap + bottom_margin);
    return page;
}

/// The series on the page, thinned: of each run of consecutive points within one column of the
/// PNG's pixels, only the first, the lowest, the highest and the last, in their order. The line
/// looks the same at that resolution, and a series of 10^5 points (a long run) costs no more to
/// draw, in time, memory or SVG bytes, than about four points per column.
std::vector<Vec2> thinned_points(const PlotSeries& s, const PlotPage& page, const PanelPage& p) {
    auto column = [&](std::size_t i) {
        return std::floor(png_scale * p.page_x(page.left, s.x[i]));
    };
    std::vector<Vec2> points;
    for (std::size_t first = 0; first < s.x.size();) {
        std::size_t end = first;
        std::size_t lowest = first;
        std::size_t highest = first;
        for (; end < s.x.size() && column(end) == column(first); ++end) {
            if (s.y[end] < s.y[lowest]) lowest = end;
            if (s.y[end] > s.y[highest]) highest = end;
        }
        std::array<std::size_t, 4> kept = {first, lowest, highest, end - 1};
        std::sort(kept.begin(), kept.end());
        for (std::size_t k = 0; k < kept.size(); ++k) {
            if (k > 0 && kept[k] == kept[k - 1]) continue;
            points.push_back({p.page_x(page.left, s.x[kept[k]]), p.page_y(s.y[kept[k]])});
        }
        first = end;
    }
    return points;
}

void draw_series(cairo_t* cr, const PlotPage& page, const PanelPage& p) {
    cairo_save(cr);
    cairo_rectangle(cr, page.left, p.top, plot_size, panel_height);
    cairo_clip(cr);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    for (const PlotSeries& s : p.panel->series) {
        if (s.x.empty()) continue;
        set_color(cr, s.color);
        if (s.x.size() == 1) {  // no line to draw: a dot
            cairo_arc(cr, p.page_x(page.left, s.x[0]), p.page_y(s.y[0]), 2.0 * s.line_width, 0.0,
                      2.0 * std::numbers::pi);
            cairo_fill(cr);
            continue;
        }
        const std::vector<Vec2> points = thinned_points(s, page, p);
        cairo_move_to(cr, points[0].x, points[0].y);
        for (std::size_t i = 1; i < points.size(); ++i) cairo_line_to(cr, points[i].x, points[i].y);
        cairo_set_line_width(cr, s.line_width);
        cairo_stroke(cr);
    }
    cairo_restore(cr);
}

/// Grid, frame, ticks and tick labels of a panel (x labels only on the lowest), and its y name.
void draw_panel_axes(cairo_t* cr, const PlotPage& page, const PanelPage& p, bool lowest) {
    const double bottom = p.top + panel_height;
    set_color(cr, grid_color);
    cairo_set_line_width(cr, 0.6);
    for (const double v : page.x_ticks.values) {
        cairo_move_to(cr, p.page_x(page.left, v), p.top);
        cairo_line_to(cr, p.page_x(page.left, v), bottom);
    }
    for (const double v : p.y_ticks.values) {
        cairo_move_to(cr, page.left, p.page_y(v));
        cairo_line_to(cr, page.left + plot_size, p.page_y(v));
    }
    cairo_stroke(cr);

    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    cairo_set_line_width(cr, 1.0);
    cairo_rectangle(cr, page.left, p.top, plot_size, panel_height);
    set_font(cr, font_size);
    for (std::size_t i = 0; i < page.x_ticks.values.size(); ++i) {
        const double x = p.page_x(page.left, page.x_ticks.values[i]);
        cairo_move_to(cr, x, bottom);
        cairo_line_to(cr, x, bottom + tick_length);
        if (lowest)
            draw_text(cr, page.x_ticks.labels[i], x, bottom + tick_length + label_gap, 0.5, 0.0);
    }
    for (std::size_t i = 0; i < p.y_ticks.values.size(); ++i) {
        const double y = p.page_y(p.y_ticks.values[i]);
        cairo_move_to(cr, page.left, y);
        cairo_line_to(cr, page.left - tick_length, y);
        draw_text(cr, p.y_ticks.labels[i], page.left - tick_length - label_gap, y, 1.0, 0.5);
    }
    cairo_stroke(cr);

    // The y name reads bottom to top along the axis, as a Figure's longer names do.
    set_font(cr, font_size + 1.0, true);
    cairo_save(cr);
    cairo_translate(cr, page.y_name_x, p.top + 0.5 * panel_height);
    cairo_rotate(cr, -0.5 * std::numbers::pi);
    draw_text(cr, p.panel->y_name, 0.0, 0.0, 0.5, 0.5);
    cairo_restore(cr);
}

void draw_plot(cairo_t* cr, const PlotPage& page, const LinePlot& plot) {
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_paint(cr);
    for (std::size_t i = 0; i < page.panels.size(); ++i) {
        const bool lowest = i + 1 == page.panels.size();
        draw_panel_axes(cr, page, page.panels[i], lowest);
        draw_series(cr, page, page.panels[i]);
    }
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    const double bottom = page.panels.back().top + panel_height;
    set_font(cr, font_size + 1.0, true);
    draw_text(cr, plot.x_name, page.left + 0.5 * plot_size, bottom + tick_length + 3.0 * font_size,
              0.5, 0.5);
    if (!plot.title.empty()) {
        set_font(cr, title_font_size);
        draw_text(cr, plot.title, page.left + 0.5 * plot_size,
                  page.panels.front().top - 0.5 * title_room, 0.5, 0.5);
    }
}

}  // namespace

void save_plot(const LinePlot& plot, const std::filesystem::path& path) {
    const PictureFormat format = picture_format(path);
    check(plot);
    const PlotPage page = plot_layout(plot);
    write_picture(path, format, page.width, page.height,
                  [&](cairo_t* cr) { draw_plot(cr, page, plot); });
}

}  // namespace slc
