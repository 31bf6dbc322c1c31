// Internals of the picture module shared by its sources: page constants, the layers a Figure
// holds, colour maps, tick and text helpers, and the page layout (render_layout.cpp); drawing and
// output live in render.cpp, which also writes the line plots of plot.cpp.
#pragma once

#include <cairo.h>

#include <array>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "slc/io/render.hpp"

namespace slc::render_detail {

// Page layout in pixels of the SVG (points) and of the PNG before its 2x scale.
inline constexpr double plot_size = 560.0;       // edge of the square plot area
inline constexpr double min_left_margin = 80.0;  // room for y tick labels and the "y" axis label
inline constexpr double right_margin = 30.0;     // room for half of the last x tick label
inline constexpr double top_margin = 20.0;
inline constexpr double title_room = 34.0;  // added to the top margin when there is a title
inline constexpr double bottom_margin = 60.0;
inline constexpr double side_gap = 24.0;  // between the plot and the legend / colour-bar column
inline constexpr double min_side_width = 150.0;
inline constexpr double tick_length = 5.0;
inline constexpr double label_gap = 4.0;  // between a tick and its label
inline constexpr double font_size = 13.0;
inline constexpr double title_font_size = 16.0;
inline constexpr double legend_row = 20.0;
inline constexpr double legend_sample = 28.0;  // length of the line sample of a legend entry
inline constexpr double legend_pad = 8.0;
/// The legend lists at most this many labelled layers (the first ones) and then a row
/// "… and n more": a row per layer would make a picture of thousands of layers taller than
/// cairo draws (32767 pixels).
inline constexpr std::size_t max_legend_entries = 40;
inline constexpr double colorbar_width = 16.0;
inline constexpr double colorbar_max_height = 300.0;
inline constexpr double colorbar_min_height = 120.0;  // below a long legend the page grows instead
inline constexpr double png_scale = 2.0;  // PNG pixels per layout pixel, for sharp lines and text
inline constexpr int max_ticks = 7;
inline const char* const font_family = "DejaVu Sans";

struct FieldLayer {
    ScalarGrid grid;
    std::string label;
    bool diverging = false;
};
/// How a layer's lines are stroked.
struct Pen {
    Color color;
    double width = 0.0;
};
struct BoxesLayer {
    std::vector<Box> boxes;
    Pen pen;
};
struct TrianglesLayer {
    std::vector<Vec2> vertices;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    Pen pen;
};
struct CurvesLayer {
    std::vector<std::vector<Vec2>> paths;
    std::string label;
    Pen pen;
    bool closed = true;
};
struct PointsLayer {
    std::vector<Vec2> points;
    Color color;
    double radius = 0.0;
};
/// Curves whose segments are coloured by a value at each vertex (the mean of their ends'), on the
/// colour map of a field.
struct ValuesLayer {
    std::vector<std::vector<Vec2>> paths;
    std::vector<std::vector<double>> values;  ///< one per vertex of each path
    std::string label;
    bool diverging = false;
    double line_width = 0.0;
};
struct ArrowsLayer {
    std::vector<Vec2> at;
    std::vector<Vec2> vec;
    double scale = 0.0;
    Color color;
};
using LayerItem = std::variant<FieldLayer, BoxesLayer, TrianglesLayer, CurvesLayer, PointsLayer,
                               ValuesLayer, ArrowsLayer>;
using Layers = std::vector<const LayerItem*>;

template <class... F>
struct Overloaded : F... {
    using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

/// The values mapped to the two ends of the colour map: ±max|v| when diverging, else min, max.
struct FieldRange {
    double lo = 0.0;
    double hi = 1.0;
    double t(double v) const { return (v - lo) / (hi - lo); }
};

/// Tick values i·step in [lo, hi], step 1, 2 or 5 × 10^e, the finest giving at most max_ticks.
struct Ticks {
    std::vector<double> values;
    std::vector<std::string> labels;
};

/// Where things go on the page, and the map from the plane to it (y up).
struct Page {
    Box view;
    double width = 0.0;
    double height = 0.0;
    double plot_x = 0.0;  // top-left corner of the plot square
    double plot_y = 0.0;
    double side_x = 0.0;        // left edge of the legend / colour-bar column
    double colorbar_top = 0.0;  // top of the colour bar itself; its label sits above
    double colorbar_height = 0.0;
    Ticks x_ticks;
    Ticks y_ticks;
    std::string x_name = "x";  // below the x ticks
    std::string y_name = "y";  // left of the y ticks, upright when one character, else turned

    double scale() const { return plot_size / view.width(); }
    Vec2 to_page(Vec2 p) const {
        return {plot_x + (p.x - view.lo.x) * scale(), plot_y + (view.hi.y - p.y) * scale()};
    }
};

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using ContextPtr = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

/// A colour from its hex code 0xRRGGBB.
constexpr Color rgb(int hex) {
    return {((hex >> 16) & 0xff) / 255.0, ((hex >> 8) & 0xff) / 255.0, (hex & 0xff) / 255.0, 1.0};
}

std::span<const Color> color_map(bool diverging);
/// The map's colour at t in [0, 1].
Color map_color(std::span<const Color> anchors, double t);
/// The range of the finite values (see FieldRange); {−1, 1} when there is none.
FieldRange value_range(std::span<const double> values, bool diverging);
FieldRange field_range(const FieldLayer& field);
FieldRange field_range(const ValuesLayer& layer);
/// A number as printed by fmt, made typographic ("−1.5e−5").
std::string typeset(std::string s);
Ticks nice_ticks(double lo, double hi);
void set_font(cairo_t* cr, double size, bool italic = false);
double text_width(cairo_t* cr, const std::string& s);
/// Draws s with its box anchored at (x, y); see render_layout.cpp.
void draw_text(cairo_t* cr, const std::string& s, double x, double y, double ax, double ay);
void set_color(cairo_t* cr, Color c);
/// What the colour bar shows: the label, map and range of the last layer coloured by values (a
/// field or values on curves).
struct ColorScale {
    std::string label;
    bool diverging = false;
    FieldRange range;
};
/// The colour scale of the last layer coloured by values, if any.
std::optional<ColorScale> color_scale(const Layers& layers);
/// The labelled curve layers, in order, the first max_legend_entries of them: the legend's
/// entries.
std::vector<const CurvesLayer*> legend_entries(const Layers& layers);
/// The legend's last row, "… and n more", for the labelled layers beyond max_legend_entries;
/// empty if there are none.
std::string legend_overflow(const Layers& layers);
/// The labels of a colour bar: top, bottom, and 0 in between when it lies inside the range.
std::vector<std::pair<double, std::string>> colorbar_labels(const FieldRange& range);
/// Height of the legend box (0 without labelled curves).
double legend_height(const Layers& layers);
/// Width of the legend box (0 without labelled curves); sets the legend's font on cr.
double legend_width(cairo_t* cr, const Layers& layers);
/// Places plot, title, legend and colour bar for a view and its layers.
Page layout(cairo_t* cr, const Box& view, const std::string& title, const Layers& layers);

// ---- output (render.cpp) ----

enum class PictureFormat { svg, png };
/// The format path's extension names, .svg or .png in any case; InvalidInput for any other.
PictureFormat picture_format(const std::filesystem::path& path);
/// Paints a whole page on cr, in layout pixels.
using DrawPage = std::function<void(cairo_t* cr)>;
/// Draws a width × height page (layout pixels; the PNG at png_scale) and writes it to path
/// atomically. InvalidInput when cairo fails or the file cannot be written.
void write_picture(const std::filesystem::path& path, PictureFormat format, double width,
                   double height, const DrawPage& draw);

/// Throws InvalidInput "cannot draw PATH: reason" unless status is CAIRO_STATUS_SUCCESS.
void check(cairo_status_t status, const std::filesystem::path& path);

}  // namespace slc::render_detail
