// The picture module's page layout: colour maps, tick values, text, and where plot, title, legend
// and colour bar go on the page.
#include "render_layout.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace slc::render_detail {

// ColorBrewer RdBu (7 classes), blue for negative; and viridis at 9 anchors. Both are
// interpolated linearly between anchors, the colour bar with the same stops.
constexpr std::array<Color, 7> diverging_map = {rgb(0x2166ac), rgb(0x67a9cf), rgb(0xd1e5f0),
                                                rgb(0xf7f7f7), rgb(0xfddbc7), rgb(0xef8a62),
                                                rgb(0xb2182b)};
constexpr std::array<Color, 9> sequential_map = {rgb(0x440154), rgb(0x472d7b), rgb(0x3b528b),
                                                 rgb(0x2c728e), rgb(0x21918c), rgb(0x28ae80),
                                                 rgb(0x5ec962), rgb(0xaddc30), rgb(0xfde725)};

std::span<const Color> color_map(bool diverging) {
    if (diverging) return diverging_map;
    return sequential_map;
}

/// The map's colour at t in [0, 1].
Color map_color(std::span<const Color> anchors, double t) {
    const double s = std::clamp(t, 0.0, 1.0) * static_cast<double>(anchors.size() - 1);
    const std::size_t i = std::min(static_cast<std::size_t>(s), anchors.size() - 2);
    const double f = s - static_cast<double>(i);
    const Color& a = anchors[i];
    const Color& b = anchors[i + 1];
    return {a.r + f * (b.r - a.r), a.g + f * (b.g - a.g), a.b + f * (b.b - a.b), 1.0};
}

FieldRange value_range(std::span<const double> values, bool diverging) {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (const double v : values) {
        if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    }
    if (lo > hi) return {-1.0, 1.0};  // no finite value at all
    if (diverging) {
        const double m = std::max(std::abs(lo), std::abs(hi));
        return m > 0.0 ? FieldRange{-m, m} : FieldRange{-1.0, 1.0};
    }
    if (lo == hi) return {lo - 0.5, hi + 0.5};
    return {lo, hi};
}

FieldRange field_range(const FieldLayer& field) {
    return value_range(field.grid.values, field.diverging);
}

FieldRange field_range(const ValuesLayer& layer) {
    std::vector<double> all;
    for (const auto& v : layer.values) all.insert(all.end(), v.begin(), v.end());
    return value_range(all, layer.diverging);
}

// ---- numbers and text -------------------------------------------------------------------------

/// A number as printed by fmt, made typographic: "-1.5e-05" becomes "−1.5e−5" (minus signs,
/// no "+" or leading zeros in the exponent).
std::string typeset(std::string s) {
    if (const std::size_t e = s.find('e'); e != std::string::npos) {
        std::size_t digits = e + 1;
        if (digits < s.size() && s[digits] == '+') s.erase(digits, 1);
        if (digits < s.size() && s[digits] == '-') ++digits;
        while (digits + 1 < s.size() && s[digits] == '0') s.erase(digits, 1);
    }
    for (std::size_t at = s.find('-'); at != std::string::npos; at = s.find('-', at)) {
        s.replace(at, 1, "\u2212");
    }
    return s;
}

Ticks nice_ticks(double lo, double hi) {
    const double range = hi - lo;
    int e = static_cast<int>(std::floor(std::log10(range))) - 2;
    for (;; ++e) {
        for (const int m : {1, 2, 5}) {
            const double step = m * std::pow(10.0, e);
            const double first = std::ceil(lo / step);
            const double last = std::floor(hi / step);
            // NaN or inf when the step underflows: try a larger one.
            if (!(last - first + 1 <= max_ticks)) continue;
            Ticks ticks;
            const int decimals = std::max(0, -e);
            const bool scientific = e >= 6 || e <= -6;  // else too many digits
            for (double i = first; i <= last; i += 1.0) {
                const double v = std::abs(i) < 0.5 ? 0.0 : i * step;  // never "-0"
                ticks.values.push_back(v);
                ticks.labels.push_back(typeset(scientific ? fmt::format("{:g}", v)
                                                          : fmt::format("{:.{}f}", v, decimals)));
            }
            return ticks;
        }
    }
}

void set_font(cairo_t* cr, double size, bool italic) {
    cairo_select_font_face(cr, font_family,
                           italic ? CAIRO_FONT_SLANT_ITALIC : CAIRO_FONT_SLANT_NORMAL,
                           CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, size);
}

double text_width(cairo_t* cr, const std::string& s) {
    cairo_text_extents_t e;
    cairo_text_extents(cr, s.c_str(), &e);
    return e.x_advance;
}

/// Draws s with its box anchored at (x, y): ax = 0, ½, 1 puts x at its left, centre or right;
/// ay the same from the top of a digit to the baseline, so labels line up on their digits.
void draw_text(cairo_t* cr, const std::string& s, double x, double y, double ax, double ay) {
    cairo_text_extents_t digit;
    cairo_text_extents(cr, "0", &digit);
    const double cap = -digit.y_bearing;
    cairo_move_to(cr, x - ax * text_width(cr, s), y - ay * cap + cap);
    cairo_show_text(cr, s.c_str());
}

void set_color(cairo_t* cr, Color c) { cairo_set_source_rgba(cr, c.r, c.g, c.b, c.a); }

// ---- layout -----------------------------------------------------------------------------------

std::optional<ColorScale> color_scale(const Layers& layers) {
    std::optional<ColorScale> scale;
    for (const LayerItem* item : layers) {
        if (const auto* f = std::get_if<FieldLayer>(item))
            scale = ColorScale{f->label, f->diverging, field_range(*f)};
        if (const auto* v = std::get_if<ValuesLayer>(item))
            scale = ColorScale{v->label, v->diverging, field_range(*v)};
    }
    return scale;
}

namespace {

std::vector<const CurvesLayer*> labelled_layers(const Layers& layers) {
    std::vector<const CurvesLayer*> labelled;
    for (const LayerItem* item : layers) {
        const auto* c = std::get_if<CurvesLayer>(item);
        if (c != nullptr && !c->label.empty()) labelled.push_back(c);
    }
    return labelled;
}

}  // namespace

std::vector<const CurvesLayer*> legend_entries(const Layers& layers) {
    std::vector<const CurvesLayer*> entries = labelled_layers(layers);
    if (entries.size() > max_legend_entries) entries.resize(max_legend_entries);
    return entries;
}

std::string legend_overflow(const Layers& layers) {
    const std::size_t n = labelled_layers(layers).size();
    return n > max_legend_entries ? fmt::format("… and {} more", n - max_legend_entries)
                                  : std::string();
}

/// The labels of a colour bar: top, bottom, and 0 in between when it lies inside the range.
std::vector<std::pair<double, std::string>> colorbar_labels(const FieldRange& range) {
    auto label = [](double v) { return typeset(fmt::format("{:.3g}", v + 0.0)); };  // no "-0"
    std::vector<std::pair<double, std::string>> labels = {{range.hi, label(range.hi)},
                                                          {range.lo, label(range.lo)}};
    // 0 only where it does not crowd the end labels (at least 8% of the bar away).
    const double t0 = range.t(0.0);
    if (t0 > 0.08 && t0 < 0.92) labels.emplace_back(0.0, "0");
    return labels;
}

double legend_height(const Layers& layers) {
    // The entries, and a row "… and n more" beyond max_legend_entries.
    const std::size_t labelled = labelled_layers(layers).size();
    const std::size_t n = std::min(labelled, max_legend_entries) + (labelled > max_legend_entries);
    return n == 0 ? 0.0 : 2 * legend_pad + legend_row * static_cast<double>(n);
}

double legend_width(cairo_t* cr, const Layers& layers) {
    const std::vector<const CurvesLayer*> entries = legend_entries(layers);
    if (entries.empty()) return 0.0;
    set_font(cr, font_size);
    double text = 0.0;
    for (const CurvesLayer* c : entries) text = std::max(text, text_width(cr, c->label));
    return std::max(3 * legend_pad + legend_sample + text,
                    2 * legend_pad + text_width(cr, legend_overflow(layers)));
}

/// Width the side column needs for the legend and the colour bar.
double side_width(cairo_t* cr, const Layers& layers) {
    double w = std::max(min_side_width, legend_width(cr, layers));
    set_font(cr, font_size);
    if (const auto scale = color_scale(layers)) {
        w = std::max(w, text_width(cr, scale->label));
        for (const auto& [v, s] : colorbar_labels(scale->range)) {
            w = std::max(w, colorbar_width + tick_length + label_gap + text_width(cr, s));
        }
    }
    return w;
}

Page layout(cairo_t* cr, const Box& view, const std::string& title, const Layers& layers) {
    Page page;
    page.view = view;
    page.x_ticks = nice_ticks(view.lo.x, view.hi.x);
    page.y_ticks = nice_ticks(view.lo.y, view.hi.y);
    set_font(cr, font_size);
    double y_label_width = 0.0;
    for (const std::string& s : page.y_ticks.labels) {
        y_label_width = std::max(y_label_width, text_width(cr, s));
    }
    // tick, gap, widest label, gap, the axis name "y" (about one em), margin
    page.plot_x =
        std::max(min_left_margin, tick_length + label_gap + y_label_width + 2.5 * font_size + 8.0);
    page.plot_y = top_margin + (title.empty() ? 0.0 : title_room);
    const double plot_bottom = page.plot_y + plot_size;
    // The side column: the legend at the top, the colour bar's label and the bar below it.
    const double legend = legend_height(layers);
    double side_bottom = page.plot_y + legend;
    if (color_scale(layers)) {
        page.colorbar_top = side_bottom + (legend > 0.0 ? 2.0 * font_size : 0.0) + 1.8 * font_size;
        page.colorbar_height = std::max(
            colorbar_min_height, std::min(colorbar_max_height, plot_bottom - page.colorbar_top));
        side_bottom = page.colorbar_top + page.colorbar_height + font_size;
    }
    page.height = std::ceil(std::max(plot_bottom + bottom_margin, side_bottom + top_margin));
    if (side_bottom > page.plot_y) {
        page.side_x = page.plot_x + plot_size + side_gap;
        page.width = std::ceil(page.side_x + side_width(cr, layers) + 2.0 * legend_pad);
    } else {
        page.width = std::ceil(page.plot_x + plot_size + right_margin);
    }
    return page;
}

}  // namespace slc::render_detail
