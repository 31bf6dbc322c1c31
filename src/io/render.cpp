// Pictures of interfaces, trees and fields drawn with cairo in the style of a journal figure: the
// square view box on a square plot with ticks, a thin frame, an optional title, a legend of the
// labelled curves and a colour bar for a field, written atomically as SVG or PNG.
#include "slc/io/render.hpp"

#include <cairo-svg.h>
#include <cairo.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <numbers>
#include <variant>

#include "render_layout.hpp"
#include "slc/core/error.hpp"
#include "slc/io/interface_json.hpp"

namespace slc {
using render_detail::check;
namespace {

using namespace render_detail;

// ---- layers -----------------------------------------------------------------------------------

/// The field as an image, one pixel per sample, top row = highest y; NaN transparent.
SurfacePtr field_image(const FieldLayer& field) {
    const ScalarGrid& g = field.grid;
    SurfacePtr image(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, g.nx, g.ny),
                     &cairo_surface_destroy);
    cairo_surface_flush(image.get());
    unsigned char* data = cairo_image_surface_get_data(image.get());
    const int stride = cairo_image_surface_get_stride(image.get());
    const FieldRange range = field_range(field);
    const std::span<const Color> map = color_map(field.diverging);
    for (int j = 0; j < g.ny; ++j) {
        auto* row = reinterpret_cast<std::uint32_t*>(
            data + static_cast<std::ptrdiff_t>(g.ny - 1 - j) * stride);
        for (int i = 0; i < g.nx; ++i) {
            const double v = g.values[static_cast<std::size_t>(j) * g.nx + i];
            if (!std::isfinite(v)) {
                row[i] = 0;  // premultiplied transparent
                continue;
            }
            const Color c = map_color(map, range.t(v));
            auto byte = [](double x) { return static_cast<std::uint32_t>(std::lround(255.0 * x)); };
            row[i] = 0xff000000u | byte(c.r) << 16 | byte(c.g) << 8 | byte(c.b);
        }
    }
    cairo_surface_mark_dirty(image.get());
    return image;
}

void draw_field(cairo_t* cr, const Page& page, const FieldLayer& field) {
    const SurfacePtr image = field_image(field);
    const Vec2 top_left = page.to_page({field.grid.box.lo.x, field.grid.box.hi.y});
    cairo_save(cr);
    cairo_translate(cr, top_left.x, top_left.y);
    cairo_scale(cr, field.grid.box.width() * page.scale() / field.grid.nx,
                field.grid.box.height() * page.scale() / field.grid.ny);
    cairo_set_source_surface(cr, image.get(), 0.0, 0.0);
    cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
    cairo_rectangle(cr, 0.0, 0.0, field.grid.nx, field.grid.ny);
    cairo_fill(cr);
    cairo_restore(cr);
}

/// Strokes the current path with the pen's colour and width.
void stroke(cairo_t* cr, const Pen& pen) {
    set_color(cr, pen.color);
    cairo_set_line_width(cr, pen.width);
    cairo_stroke(cr);
}

void draw_boxes(cairo_t* cr, const Page& page, const BoxesLayer& layer) {
    for (const Box& b : layer.boxes) {
        const Vec2 p = page.to_page({b.lo.x, b.hi.y});
        cairo_rectangle(cr, p.x, p.y, b.width() * page.scale(), b.height() * page.scale());
    }
    stroke(cr, layer.pen);
}

void draw_triangles(cairo_t* cr, const Page& page, const TrianglesLayer& layer) {
    for (const auto& t : layer.triangles) {
        for (int k = 0; k < 3; ++k) {
            const Vec2 p = page.to_page(layer.vertices[t[k]]);
            k == 0 ? cairo_move_to(cr, p.x, p.y) : cairo_line_to(cr, p.x, p.y);
        }
        cairo_close_path(cr);
    }
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    stroke(cr, layer.pen);
}

void draw_curves(cairo_t* cr, const Page& page, const CurvesLayer& layer) {
    for (const auto& path : layer.paths) {
        bool first = true;
        for (const Vec2 v : path) {
            if (!is_finite(v)) continue;  // a broken curve is still drawn, without that vertex
            const Vec2 p = page.to_page(v);
            first ? cairo_move_to(cr, p.x, p.y) : cairo_line_to(cr, p.x, p.y);
            first = false;
        }
        if (!first && layer.closed) cairo_close_path(cr);
    }
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    stroke(cr, layer.pen);
}

void draw_points(cairo_t* cr, const Page& page, const PointsLayer& layer) {
    for (const Vec2 v : layer.points) {
        if (!is_finite(v)) continue;
        const Vec2 p = page.to_page(v);
        cairo_new_sub_path(cr);
        cairo_arc(cr, p.x, p.y, layer.radius, 0.0, 2.0 * M_PI);
    }
    set_color(cr, layer.color);
    cairo_fill(cr);
}

/// Each segment in the colour of the mean of its ends' values.
void draw_values(cairo_t* cr, const Page& page, const ValuesLayer& layer) {
    const FieldRange range = field_range(layer);
    const std::span<const Color> map = color_map(layer.diverging);
    cairo_set_line_width(cr, layer.line_width);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    for (std::size_t c = 0; c < layer.paths.size(); ++c) {
        const std::vector<Vec2>& path = layer.paths[c];
        const std::vector<double>& values = layer.values[c];
        for (std::size_t i = 0; i < path.size(); ++i) {
            const std::size_t j = (i + 1) % path.size();
            const double v = 0.5 * (values[i] + values[j]);
            if (!is_finite(path[i]) || !is_finite(path[j]) || !std::isfinite(v)) continue;
            const Vec2 a = page.to_page(path[i]), b = page.to_page(path[j]);
            cairo_move_to(cr, a.x, a.y);
            cairo_line_to(cr, b.x, b.y);
            set_color(cr, map_color(map, range.t(v)));
            cairo_stroke(cr);
        }
    }
}

/// Arrows with a filled head whose size is fixed on the page, shrunk on short arrows.
void draw_arrows(cairo_t* cr, const Page& page, const ArrowsLayer& layer) {
    constexpr double head_length = 7.0;
    constexpr double head_half_width = 2.8;
    cairo_new_path(cr);
    std::vector<std::array<Vec2, 3>> heads;
    for (std::size_t i = 0; i < layer.at.size(); ++i) {
        const Vec2 tail = page.to_page(layer.at[i]);
        const Vec2 tip = page.to_page(layer.at[i] + layer.scale * layer.vec[i]);
        const double len = distance(tail, tip);
        if (!(len > 1e-3) || !std::isfinite(len)) continue;  // nothing to see, or not finite
        const Vec2 dir = (tip - tail) / len;
        const double h = std::min(head_length, 0.4 * len);
        const Vec2 base = tip - h * dir;
        const Vec2 side = (h / head_length) * head_half_width * perp(dir);
        heads.push_back({tip, base + side, base - side});
        cairo_move_to(cr, tail.x, tail.y);
        cairo_line_to(cr, base.x + 0.3 * h * dir.x, base.y + 0.3 * h * dir.y);
    }
    stroke(cr, {layer.color, 1.0});
    for (const auto& [a, b, c] : heads) {
        cairo_move_to(cr, a.x, a.y);
        cairo_line_to(cr, b.x, b.y);
        cairo_line_to(cr, c.x, c.y);
        cairo_close_path(cr);
    }
    cairo_fill(cr);
}

void draw_layers(cairo_t* cr, const Page& page, const Layers& layers) {
    cairo_save(cr);
    cairo_rectangle(cr, page.plot_x, page.plot_y, plot_size, plot_size);
    cairo_clip(cr);
    for (const LayerItem* item : layers) {
        std::visit(Overloaded{[&](const FieldLayer& l) { draw_field(cr, page, l); },
                              [&](const BoxesLayer& l) { draw_boxes(cr, page, l); },
                              [&](const TrianglesLayer& l) { draw_triangles(cr, page, l); },
                              [&](const CurvesLayer& l) { draw_curves(cr, page, l); },
                              [&](const PointsLayer& l) { draw_points(cr, page, l); },
                              [&](const ValuesLayer& l) { draw_values(cr, page, l); },
                              [&](const ArrowsLayer& l) { draw_arrows(cr, page, l); }},
                   *item);
    }
    cairo_restore(cr);
}

// ---- frame, axes, legend, colour bar ------------------------------------------------------------

void draw_axes(cairo_t* cr, const Page& page) {
    const double bottom = page.plot_y + plot_size;
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    cairo_set_line_width(cr, 1.0);
    cairo_rectangle(cr, page.plot_x, page.plot_y, plot_size, plot_size);
    set_font(cr, font_size);
    for (std::size_t i = 0; i < page.x_ticks.values.size(); ++i) {
        const double x = page.to_page({page.x_ticks.values[i], 0.0}).x;
        cairo_move_to(cr, x, bottom);
        cairo_line_to(cr, x, bottom + tick_length);
        draw_text(cr, page.x_ticks.labels[i], x, bottom + tick_length + label_gap, 0.5, 0.0);
    }
    double widest = 0.0;
    for (std::size_t i = 0; i < page.y_ticks.values.size(); ++i) {
        const double y = page.to_page({0.0, page.y_ticks.values[i]}).y;
        cairo_move_to(cr, page.plot_x, y);
        cairo_line_to(cr, page.plot_x - tick_length, y);
        draw_text(cr, page.y_ticks.labels[i], page.plot_x - tick_length - label_gap, y, 1.0, 0.5);
        widest = std::max(widest, text_width(cr, page.y_ticks.labels[i]));
    }
    cairo_stroke(cr);
    set_font(cr, font_size + 1.0, true);
    draw_text(cr, page.x_name, page.plot_x + 0.5 * plot_size,
              bottom + tick_length + 3.0 * font_size, 0.5, 0.5);
    const double y_name_x = page.plot_x - tick_length - label_gap - widest - font_size;
    if (page.y_name.size() <= 1) {
        draw_text(cr, page.y_name, y_name_x, page.plot_y + 0.5 * plot_size, 0.5, 0.5);
        return;
    }
    // A longer name reads bottom to top along the axis, in the one em the layout leaves.
    cairo_save(cr);
    cairo_translate(cr, y_name_x, page.plot_y + 0.5 * plot_size);
    cairo_rotate(cr, -0.5 * std::numbers::pi);
    draw_text(cr, page.y_name, 0.0, 0.0, 0.5, 0.5);
    cairo_restore(cr);
}

void draw_title(cairo_t* cr, const Page& page, const std::string& title) {
    if (title.empty()) return;
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    set_font(cr, title_font_size);
    draw_text(cr, title, page.plot_x + 0.5 * plot_size, page.plot_y - 0.5 * title_room, 0.5, 0.5);
}

/// The legend at the top of the side column.
void draw_legend(cairo_t* cr, const Page& page, const Layers& layers) {
    const std::vector<const CurvesLayer*> entries = legend_entries(layers);
    if (entries.empty()) return;
    const std::string more = legend_overflow(layers);
    const double w = legend_width(cr, layers);  // sets the legend's font
    const double h = legend_height(layers);
    cairo_rectangle(cr, page.side_x + 0.5, page.plot_y + 0.5, w, h);
    cairo_set_source_rgb(cr, 0.75, 0.75, 0.75);
    cairo_set_line_width(cr, 1.0);
    cairo_stroke(cr);
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const double y = page.plot_y + legend_pad + legend_row * (static_cast<double>(i) + 0.5);
        const double x = page.side_x + legend_pad;
        cairo_move_to(cr, x, y);
        cairo_line_to(cr, x + legend_sample, y);
        cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
        stroke(cr, entries[i]->pen);
        cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
        draw_text(cr, entries[i]->label, x + legend_sample + legend_pad, y, 0.0, 0.5);
    }
    if (!more.empty()) {
        const double y =
            page.plot_y + legend_pad + legend_row * (static_cast<double>(entries.size()) + 0.5);
        draw_text(cr, more, page.side_x + legend_pad, y, 0.0, 0.5);
    }
}

/// A vertical colour bar below the legend: the label above, the range's values at the right.
void draw_colorbar(cairo_t* cr, const Page& page, const ColorScale& scale) {
    const FieldRange range = scale.range;
    const double bar_top = page.colorbar_top;
    const double height = page.colorbar_height;
    const double x = page.side_x;
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    set_font(cr, font_size);
    draw_text(cr, scale.label, x, bar_top - 0.6 * font_size, 0.0, 1.0);

    const std::span<const Color> map = color_map(scale.diverging);
    cairo_pattern_t* gradient = cairo_pattern_create_linear(0.0, bar_top + height, 0.0, bar_top);
    for (std::size_t i = 0; i < map.size(); ++i) {
        const Color& c = map[i];
        cairo_pattern_add_color_stop_rgb(
            gradient, static_cast<double>(i) / static_cast<double>(map.size() - 1), c.r, c.g, c.b);
    }
    cairo_rectangle(cr, x, bar_top, colorbar_width, height);
    cairo_set_source(cr, gradient);
    cairo_fill_preserve(cr);
    cairo_pattern_destroy(gradient);
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    cairo_set_line_width(cr, 0.8);
    for (const auto& [v, s] : colorbar_labels(range)) {
        const double y = bar_top + height * (1.0 - range.t(v));
        cairo_move_to(cr, x + colorbar_width, y);
        cairo_line_to(cr, x + colorbar_width + tick_length, y);
        draw_text(cr, s, x + colorbar_width + tick_length + label_gap, y, 0.0, 0.5);
    }
    cairo_stroke(cr);
}

void render(cairo_t* cr, const Page& page, const Layers& layers, const std::string& title) {
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_paint(cr);
    draw_layers(cr, page, layers);
    draw_axes(cr, page);
    draw_title(cr, page, title);
    draw_legend(cr, page, layers);
    if (const auto scale = color_scale(layers)) draw_colorbar(cr, page, *scale);
}

// ---- output -----------------------------------------------------------------------------------

cairo_status_t append_bytes(void* closure, const unsigned char* data, unsigned int length) {
    static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
    return CAIRO_STATUS_SUCCESS;
}

Page measured_layout(const Box& view, const std::string& title, const Layers& layers) {
    const SurfacePtr scratch(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1),
                             &cairo_surface_destroy);
    const ContextPtr cr(cairo_create(scratch.get()), &cairo_destroy);
    return layout(cr.get(), view, title, layers);
}

std::string svg_bytes(double width, double height, const DrawPage& draw,
                      const std::filesystem::path& path) {
    std::string bytes;
    const SurfacePtr surface(
        cairo_svg_surface_create_for_stream(&append_bytes, &bytes, width, height),
        &cairo_surface_destroy);
    {
        const ContextPtr cr(cairo_create(surface.get()), &cairo_destroy);
        draw(cr.get());
        check(cairo_status(cr.get()), path);
    }
    cairo_surface_finish(surface.get());
    check(cairo_surface_status(surface.get()), path);
    return bytes;
}

std::string png_bytes(double width, double height, const DrawPage& draw,
                      const std::filesystem::path& path) {
    const SurfacePtr surface(
        cairo_image_surface_create(CAIRO_FORMAT_RGB24, static_cast<int>(png_scale * width),
                                   static_cast<int>(png_scale * height)),
        &cairo_surface_destroy);
    {
        const ContextPtr cr(cairo_create(surface.get()), &cairo_destroy);
        cairo_scale(cr.get(), png_scale, png_scale);
        draw(cr.get());
        check(cairo_status(cr.get()), path);
    }
    std::string bytes;
    check(cairo_surface_write_to_png_stream(surface.get(), &append_bytes, &bytes), path);
    return bytes;
}

void check_positive(double v, const char* what) {
    if (!(v > 0.0) || !std::isfinite(v)) {
        throw InvalidInput(fmt::format("{} must be positive and finite, got {}", what, v));
    }
}

}  // namespace

namespace render_detail {

void check(cairo_status_t status, const std::filesystem::path& path) {
    if (status != CAIRO_STATUS_SUCCESS) {
        throw InvalidInput(
            fmt::format("cannot draw {}: {}", path.string(), cairo_status_to_string(status)));
    }
}

PictureFormat picture_format(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    if (ext == ".svg") return PictureFormat::svg;
    if (ext == ".png") return PictureFormat::png;
    throw InvalidInput(
        fmt::format("cannot save {}: the picture must end in .svg or .png", path.string()));
}

void write_picture(const std::filesystem::path& path, PictureFormat format, double width,
                   double height, const DrawPage& draw) {
    write_file_atomic(path, format == PictureFormat::svg ? svg_bytes(width, height, draw, path)
                                                         : png_bytes(width, height, draw, path));
}

}  // namespace render_detail

struct Figure::Layer {
    LayerItem item;
};

Color palette_color(std::size_t i) {
    // Tableau 10 without its yellow and grey, which are too faint on white.
    static constexpr std::array<Color, 8> palette = {rgb(0x4e79a7), rgb(0xf28e2b), rgb(0xe15759),
                                                     rgb(0x76b7b2), rgb(0x59a14f), rgb(0xb07aa1),
                                                     rgb(0x9c755f), rgb(0xff9da7)};
    return palette[i % palette.size()];
}

Color sequence_color(double t) {
    // Viridis without its palest yellow end, which is too faint for a line on white.
    return map_color(color_map(false), 0.85 * std::clamp(t, 0.0, 1.0));
}

Figure::Figure(Box view, std::string title) : title_(std::move(title)) {
    const double w = view.width();
    const double h = view.height();
    if (!std::isfinite(w) || !std::isfinite(h) || w < 0.0 || h < 0.0 || std::max(w, h) <= 0.0) {
        throw InvalidInput(fmt::format("figure view box [{}, {}] x [{}, {}] is empty", view.lo.x,
                                       view.hi.x, view.lo.y, view.hi.y));
    }
    // Square aspect: the shorter side grows about the centre.
    const double half = 0.5 * std::max(w, h);
    const Vec2 c = view.center();
    view_ = {{c.x - half, c.y - half}, {c.x + half, c.y + half}};
}

void Figure::add_field(const ScalarGrid& field, const std::string& label, bool diverging) {
    if (field.nx <= 0 || field.ny <= 0 ||
        field.values.size() != static_cast<std::size_t>(field.nx) * field.ny) {
        throw InvalidInput(fmt::format(
            "field {}: a {} x {} grid needs {} values, got {}", label, field.nx, field.ny,
            std::max(field.nx, 0) * std::max(field.ny, 0), field.values.size()));
    }
    check_positive(field.box.width(), "field box width");
    check_positive(field.box.height(), "field box height");
    layers_.push_back(std::make_shared<Layer>(Layer{FieldLayer{field, label, diverging}}));
}

void Figure::add_boxes(std::span<const Box> boxes, Color color, double line_width) {
    check_positive(line_width, "line width");
    layers_.push_back(std::make_shared<Layer>(
        Layer{BoxesLayer{{boxes.begin(), boxes.end()}, {color, line_width}}}));
}

void Figure::add_triangles(std::span<const Vec2> vertices,
                           std::span<const std::array<std::uint32_t, 3>> triangles, Color color,
                           double line_width) {
    check_positive(line_width, "line width");
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        for (const std::uint32_t v : triangles[t]) {
            if (v >= vertices.size()) {
                throw InvalidInput(fmt::format("triangle {} has vertex {}, but there are only {}",
                                               t, v, vertices.size()));
            }
        }
    }
    layers_.push_back(
        std::make_shared<Layer>(Layer{TrianglesLayer{{vertices.begin(), vertices.end()},
                                                     {triangles.begin(), triangles.end()},
                                                     {color, line_width}}}));
}

void Figure::add_curves(const Interface& curves, const std::string& label, Color color,
                        double line_width) {
    check_positive(line_width, "line width");
    layers_.push_back(std::make_shared<Layer>(
        Layer{CurvesLayer{curves.curves(), label, {color, line_width}, true}}));
}

void Figure::add_polyline(std::span<const Vec2> points, const std::string& label, Color color,
                          double line_width) {
    check_positive(line_width, "line width");
    layers_.push_back(std::make_shared<Layer>(Layer{CurvesLayer{
        {std::vector<Vec2>(points.begin(), points.end())}, label, {color, line_width}, false}}));
}

void Figure::add_curve_values(const Interface& curves, std::span<const double> values,
                              const std::string& label, bool diverging, double line_width) {
    check_positive(line_width, "line width");
    if (values.size() != curves.size()) {
        throw InvalidInput(fmt::format("values on curves {}: {} vertices but {} values", label,
                                       curves.size(), values.size()));
    }
    ValuesLayer layer{curves.curves(), {}, label, diverging, line_width};
    for (std::size_t c = 0; c < curves.curve_count(); ++c) {
        const std::size_t first = curves.offsets()[c];
        layer.values.emplace_back(
            values.begin() + static_cast<std::ptrdiff_t>(first),
            values.begin() + static_cast<std::ptrdiff_t>(first + layer.paths[c].size()));
    }
    layers_.push_back(std::make_shared<Layer>(Layer{std::move(layer)}));
}

void Figure::add_points(std::span<const Vec2> points, Color color, double radius) {
    check_positive(radius, "point radius");
    layers_.push_back(
        std::make_shared<Layer>(Layer{PointsLayer{{points.begin(), points.end()}, color, radius}}));
}

void Figure::add_arrows(std::span<const Vec2> at, std::span<const Vec2> vec, double scale,
                        Color color) {
    if (at.size() != vec.size()) {
        throw InvalidInput(
            fmt::format("arrows: {} positions but {} vectors", at.size(), vec.size()));
    }
    if (!std::isfinite(scale))
        throw InvalidInput(fmt::format("arrow scale must be finite, got {}", scale));
    layers_.push_back(std::make_shared<Layer>(
        Layer{ArrowsLayer{{at.begin(), at.end()}, {vec.begin(), vec.end()}, scale, color}}));
}

void Figure::save_grid(std::span<const Figure> figures, int columns,
                       const std::filesystem::path& path) {
    if (figures.empty()) throw InvalidInput("a grid of pictures needs at least one");
    if (columns < 1) throw InvalidInput(fmt::format("a grid needs a column, got {}", columns));
    const PictureFormat format = picture_format(path);
    std::vector<Layers> layers(figures.size());
    std::vector<Page> pages;
    double cell_width = 0.0, cell_height = 0.0;
    for (std::size_t i = 0; i < figures.size(); ++i) {
        for (const auto& layer : figures[i].layers_) layers[i].push_back(&layer->item);
        Page page = measured_layout(figures[i].view_, figures[i].title_, layers[i]);
        page.x_name = figures[i].x_name_;
        page.y_name = figures[i].y_name_;
        cell_width = std::max(cell_width, page.width);
        cell_height = std::max(cell_height, page.height);
        pages.push_back(std::move(page));
    }
    const std::size_t across = std::min(figures.size(), static_cast<std::size_t>(columns));
    const std::size_t rows = (figures.size() + across - 1) / across;
    // A PNG's png_scale makes 2 pixels of a layout pixel; many panels are drawn smaller.
    const double shrink =
        format == PictureFormat::png
            ? std::min(1.0, 2400.0 / (png_scale * cell_width * static_cast<double>(across)))
            : 1.0;
    write_picture(path, format, shrink * cell_width * static_cast<double>(across),
                  shrink * cell_height * static_cast<double>(rows), [&](cairo_t* cr) {
                      cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
                      cairo_paint(cr);
                      cairo_scale(cr, shrink, shrink);
                      for (std::size_t i = 0; i < figures.size(); ++i) {
                          cairo_save(cr);
                          cairo_translate(cr, cell_width * static_cast<double>(i % across),
                                          cell_height * static_cast<double>(i / across));
                          // render() paints its page white: only its own cell.
                          cairo_rectangle(cr, 0.0, 0.0, cell_width, cell_height);
                          cairo_clip(cr);
                          render(cr, pages[i], layers[i], figures[i].title_);
                          cairo_restore(cr);
                      }
                  });
}

void Figure::save(const std::filesystem::path& path) const {
    const PictureFormat format = picture_format(path);
    Layers layers;
    for (const auto& layer : layers_) layers.push_back(&layer->item);
    Page page = measured_layout(view_, title_, layers);
    page.x_name = x_name_;
    page.y_name = y_name_;
    write_picture(path, format, page.width, page.height,
                  [&](cairo_t* cr) { render(cr, page, layers, title_); });
}

}  // namespace slc
