// Shaded pictures of closed triangle surfaces drawn with cairo: an orthographic camera from an
// azimuth and an elevation, back faces culled, the front faces painted far to near by the depth
// of their centroids (the painter's algorithm) in flat Lambert shading, written atomically as
// PNG or SVG through render.cpp's output; below the surface, a band with an axis triad, a colour
// bar when the surface is coloured by a quantity, and a scale bar.
#include "slc/io/surface_picture.hpp"

#include <cairo.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include "render_layout.hpp"
#include "slc/core/box3.hpp"
#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/vec2.hpp"
#include "slc/io/render.hpp"

namespace slc {
namespace {

using namespace render_detail;

/// Cairo draws images of at most this many pixels a side.
constexpr int max_picture_size = 32767;
/// Empty band around the surface, as a fraction of the picture's shorter side.
constexpr double margin_fraction = 0.05;
/// Title font size as a fraction of the picture's shorter side, and its least size; the title
/// takes a band two font sizes tall at the top.
constexpr double title_fraction = 0.03;
constexpr double min_title_size = 10.0;
/// Share of the light that reaches every front face whatever its slope, so that faces turned
/// away from the light still show the colour.
constexpr double ambient = 0.25;
/// A face drawn without its edge is grown by half this width (pixels) on every side, over the
/// hairline cracks that antialiasing leaves between neighbours (paint).
constexpr double seam_width = 1.0;
/// Edges, when drawn, are this wide (pixels) and this fraction of the face's brightness.
constexpr double edge_width = 0.6;
constexpr double edge_brightness = 0.55;
/// Surfaces with more triangles than this are drawn without edges: the edges would cover them.
constexpr std::size_t max_edged_triangles = 20000;
/// The band of guides below the surface (triad, colour bar, scale bar), its font size and the
/// triad's arm, as fractions of the picture's shorter side; the font's least size.
constexpr double guide_band_fraction = 0.11;
constexpr double guide_font_fraction = 0.022;
constexpr double min_guide_font = 8.0;
constexpr double triad_arm_fraction = 0.045;
/// An axis whose arm is seen shorter than this fraction of its length (within 30° of the line of
/// sight) is drawn end on: its short arm would lie along another's, their labels crossed.
constexpr double min_seen_arm = 0.5;
/// The scale bar is the longest 1, 2 or 5 × 10^n at most this fraction of the width.
constexpr double scale_bar_fraction = 0.2;
/// The colour bar spans this part of the width, and is this fraction of the shorter side tall.
constexpr double colorbar_lo = 0.3;
constexpr double colorbar_hi = 0.66;
constexpr double colorbar_thickness = 0.018;
/// Up axes whose extents differ by less than this ratio count as alike (up_axis).
constexpr double alike_extent = 0.9;

/// The camera's orthonormal frame: the picture's right and up, and the direction toward the
/// viewer (right × up = toward); and the unit direction toward the light.
struct Camera {
    Vec3 right;
    Vec3 up;
    Vec3 toward;
    Vec3 light;
};

Vec3 unit(Vec3 v) { return v / norm(v); }

/// The unit vectors e1, e2, e3 of a right-handed frame whose third is the up axis: (x, y, z),
/// (z, x, y) or (y, z, x), the axes in cyclic order.
std::array<Vec3, 3> up_frame(UpAxis up) {
    const Vec3 x{1.0, 0.0, 0.0};
    const Vec3 y{0.0, 1.0, 0.0};
    const Vec3 z{0.0, 0.0, 1.0};
    switch (up) {
        case UpAxis::x:
            return {y, z, x};
        case UpAxis::y:
            return {z, x, y};
        case UpAxis::z:
            break;
    }
    return {x, y, z};
}

Camera camera(const SurfaceView& view) {
    const double a = view.azimuth * std::numbers::pi / 180.0;
    const double e = view.elevation * std::numbers::pi / 180.0;
    const auto [e1, e2, e3] = up_frame(view.up);
    Camera c;
    c.toward = std::cos(e) * std::cos(a) * e1 + std::cos(e) * std::sin(a) * e2 + std::sin(e) * e3;
    c.right = -std::sin(a) * e1 + std::cos(a) * e2;
    c.up = cross(c.toward, c.right);  // e3 up unless seen from straight above or below
    // Near the viewer, a little above and to the left: the lit and the shaded sides both show.
    c.light = unit(c.toward + 0.6 * c.up - 0.4 * c.right);
    return c;
}

/// The map from space to the page (pixels, y down): the bounding box's projection centred in
/// the part of the page below the title, scaled to fit within the margin.
struct PageMap {
    Camera camera;
    Vec2 center;     // of the projected box, in the picture's right / up coordinates
    Vec2 page_mid;   // where that centre goes on the page
    double scale{};  // pixels per unit length

    Vec2 to_page(Vec3 p) const {
        return {page_mid.x + scale * (dot(p, camera.right) - center.x),
                page_mid.y - scale * (dot(p, camera.up) - center.y)};
    }
};

double title_size(const SurfaceView& view) {
    return std::max(min_title_size, title_fraction * std::min(view.width, view.height));
}

double margin_size(const SurfaceView& view) {
    return margin_fraction * std::min(view.width, view.height);
}

/// The empty band below the surface: the margin, or the band of guides.
double bottom_size(const SurfaceView& view) {
    const double margin = margin_size(view);
    return view.guides ? std::max(margin, guide_band_fraction * std::min(view.width, view.height))
                       : margin;
}

PageMap page_map(const Box3& box, const SurfaceView& view) {
    PageMap map{camera(view), {}, {}, 1.0};
    Vec2 lo{INFINITY, INFINITY};
    Vec2 hi{-INFINITY, -INFINITY};
    for (int k = 0; k < 8; ++k) {
        const Vec3 corner{(k & 1 ? box.hi : box.lo).x, (k & 2 ? box.hi : box.lo).y,
                          (k & 4 ? box.hi : box.lo).z};
        const Vec2 p{dot(corner, map.camera.right), dot(corner, map.camera.up)};
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    const double margin = margin_size(view);
    const double top = view.title.empty() ? margin : std::max(margin, 2.0 * title_size(view));
    const double room_x = std::max(view.width - 2.0 * margin, 1.0);
    const double room_y = std::max(view.height - top - bottom_size(view), 1.0);
    const double scale = std::min(hi.x > lo.x ? room_x / (hi.x - lo.x) : INFINITY,
                                  hi.y > lo.y ? room_y / (hi.y - lo.y) : INFINITY);
    map.center = {0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y)};
    map.page_mid = {0.5 * view.width, top + 0.5 * room_y};
    if (std::isfinite(scale)) map.scale = scale;  // else the box is a point
    return map;
}

/// A front face: the surface and triangle, and three times the depth of its centroid toward
/// the viewer, the key by which faces are painted (far first; ties by surface, then triangle).
struct Facet {
    double depth3 = 0.0;
    std::uint32_t surface = 0;
    std::uint32_t triangle = 0;

    friend bool operator<(const Facet& a, const Facet& b) {
        if (a.depth3 != b.depth3) return a.depth3 < b.depth3;
        if (a.surface != b.surface) return a.surface < b.surface;
        return a.triangle < b.triangle;
    }
};

/// The faces turned toward the viewer, far to near. A closed outward surface hides its back
/// faces behind its front ones, so culling them halves the painting and changes nothing else.
std::vector<Facet> front_facets(std::span<const Surface> surfaces, const Camera& camera) {
    std::vector<Facet> facets;
    for (std::size_t i = 0; i < surfaces.size(); ++i) {
        const Surface& s = surfaces[i];
        for (std::size_t t = 0; t < s.size(); ++t) {
            const Triangle3 tri = s.triangle(t);
            if (dot(cross(tri.b - tri.a, tri.c - tri.a), camera.toward) <= 0.0) continue;
            facets.push_back({dot(tri.a + tri.b + tri.c, camera.toward),
                              static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(t)});
        }
    }
    std::sort(facets.begin(), facets.end());
    return facets;
}

/// Lambert's law with ambient light: the brightness of a face with outward normal n.
double brightness(Vec3 n, const Camera& camera) {
    return ambient + (1.0 - ambient) * std::max(0.0, dot(n, camera.light) / norm(n));
}

void set_rgb(cairo_t* cr, Color c, double brightness) {
    cairo_set_source_rgb(cr, brightness * c.r, brightness * c.g, brightness * c.b);
}

/// What painting needs of the scene: the surfaces with their vertices on the page, colours and
/// whether their edges are drawn; and the quantity the first surface is coloured by, if any.
struct Scene {
    std::span<const Surface> surfaces;
    std::vector<std::vector<Vec2>> page;  // per surface, per vertex
    std::vector<Color> colors;
    std::vector<bool> edged;
    const SurfaceColoring* coloring = nullptr;
    FieldRange range;

    /// The colour of triangle t of surface i: its quantity's at the mean of its corners, or the
    /// surface's.
    Color color(std::uint32_t i, std::uint32_t t) const {
        if (coloring == nullptr || i != 0) return colors[i];
        const TriangleIndices& tri = surfaces[i].triangles[t];
        const double v =
            (coloring->values[tri[0]] + coloring->values[tri[1]] + coloring->values[tri[2]]) / 3.0;
        return map_color(color_map(true), range.t(v));
    }
};

/// ±max|v| over the values, or ±1 when they are all zero.
FieldRange symmetric_range(std::span<const double> values) {
    double m = 0.0;
    for (const double v : values) m = std::max(m, std::abs(v));
    return m > 0.0 ? FieldRange{-m, m} : FieldRange{-1.0, 1.0};
}

Scene scene(std::span<const Surface> surfaces, const PageMap& map, const SurfaceView& view,
            const SurfaceColoring* coloring) {
    Scene sc{surfaces, {}, {}, {}, coloring, {}};
    if (coloring != nullptr) sc.range = symmetric_range(coloring->values);
    for (std::size_t i = 0; i < surfaces.size(); ++i) {
        std::vector<Vec2> page(surfaces[i].vertices.size());
        std::transform(surfaces[i].vertices.begin(), surfaces[i].vertices.end(), page.begin(),
                       [&](Vec3 p) { return map.to_page(p); });
        sc.page.push_back(std::move(page));
        sc.colors.push_back(palette_color(i));
        sc.edged.push_back(view.edges && surfaces[i].size() <= max_edged_triangles);
    }
    return sc;
}

/// The triangle p grown by `by` (pixels) on every side: each corner moved to where its two
/// edges, shifted outward, meet, and no farther than 2·by from where it was (a sliver's sharp
/// corner would otherwise reach far beyond it, as a mitred join would).
std::array<Vec2, 3> grown(const std::array<Vec2, 3>& p, double by) {
    const double orientation = cross(p[1] - p[0], p[2] - p[0]) >= 0.0 ? 1.0 : -1.0;
    std::array<Vec2, 3> outward{};  // of edge i, from p[i] to p[i + 1]
    for (int i = 0; i < 3; ++i) {
        const Vec2 e = p[(i + 1) % 3] - p[i];
        const double length = norm(e);
        if (length > 0.0) outward[i] = (orientation / length) * Vec2{e.y, -e.x};
    }
    std::array<Vec2, 3> out{};
    for (int i = 0; i < 3; ++i) {
        const Vec2 a = outward[(i + 2) % 3], b = outward[i];  // the edges meeting at p[i]
        const double meet = 1.0 + dot(a, b);
        Vec2 move = meet > 0.0 ? (by / meet) * (a + b) : Vec2{};
        const double length = norm(move);
        if (length > 2.0 * by) move = (2.0 * by / length) * move;
        out[i] = p[i] + move;
    }
    return out;
}

/// Paints the faces in order, each in its shade. A face of a surface drawn without edges is
/// filled grown by half a pixel, which covers the hairline cracks that antialiasing leaves
/// between neighbours (the background shows through at every shared edge where two partly
/// covering triangles are composited one over the other) as a stroke around it would, at a
/// fraction of a stroke's cost. A face with its edge drawn is filled and stroked with the edge,
/// the fill left out when the stroke covers the whole face anyway (in-radius below half the
/// stroke's width).
void paint(cairo_t* cr, const Scene& sc, std::span<const Facet> facets, const Camera& camera) {
    // Bevelled joins: a mitred join at a sliver's sharp corner would stick out far beyond it.
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_BEVEL);
    cairo_set_line_width(cr, edge_width);
    for (const Facet& f : facets) {
        const Surface& s = sc.surfaces[f.surface];
        const TriangleIndices& tri = s.triangles[f.triangle];
        const std::vector<Vec2>& page = sc.page[f.surface];
        const bool edged = sc.edged[f.surface];
        const std::array<Vec2, 3> corners = {page[tri[0]], page[tri[1]], page[tri[2]]};
        const std::array<Vec2, 3> p = edged ? corners : grown(corners, 0.5 * seam_width);
        cairo_move_to(cr, p[0].x, p[0].y);
        cairo_line_to(cr, p[1].x, p[1].y);
        cairo_line_to(cr, p[2].x, p[2].y);
        cairo_close_path(cr);

        const Triangle3 t = s.triangle(f.triangle);
        const double shade = brightness(cross(t.b - t.a, t.c - t.a), camera);
        const Color color = sc.color(f.surface, f.triangle);
        set_rgb(cr, color, shade);
        if (!edged) {
            cairo_fill(cr);
            continue;
        }
        const double twice_area = std::abs(cross(p[1] - p[0], p[2] - p[0]));
        const double perimeter = norm(p[1] - p[0]) + norm(p[2] - p[1]) + norm(p[0] - p[2]);
        if (2.0 * twice_area >= edge_width * perimeter) cairo_fill_preserve(cr);
        set_rgb(cr, color, edge_brightness * shade);
        cairo_stroke(cr);
    }
}

double guide_font(const SurfaceView& view) {
    return std::max(min_guide_font, guide_font_fraction * std::min(view.width, view.height));
}

/// The axis triad at the bottom left: the axes' unit vectors as seen, far ones first, each in
/// its colour (x red, y green, z blue) and labelled at its tip.
void draw_triad(cairo_t* cr, const PageMap& map, const SurfaceView& view) {
    const double arm = triad_arm_fraction * std::min(view.width, view.height);
    const double band = bottom_size(view);
    const Vec2 origin{margin_size(view) + 1.4 * arm, view.height - 0.5 * band};
    const std::array<Vec3, 3> axes = {Vec3{1.0, 0.0, 0.0}, Vec3{0.0, 1.0, 0.0},
                                      Vec3{0.0, 0.0, 1.0}};
    constexpr std::array<int, 3> hex = {0xd62728, 0x2ca02c, 0x1f77b4};
    constexpr std::array<const char*, 3> names = {"x", "y", "z"};
    std::array<int, 3> order = {0, 1, 2};
    const Camera& c = map.camera;
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return dot(axes[a], c.toward) < dot(axes[b], c.toward); });
    set_font(cr, guide_font(view), true);
    cairo_set_line_width(cr, std::max(1.0, 0.15 * guide_font(view)));
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    for (const int k : order) {
        const Vec2 d{dot(axes[k], c.right), -dot(axes[k], c.up)};
        set_color(cr, rgb(hex[k]));
        if (norm(d) >= min_seen_arm) {
            cairo_move_to(cr, origin.x, origin.y);
            cairo_line_to(cr, origin.x + arm * d.x, origin.y + arm * d.y);
            cairo_stroke(cr);
            draw_text(cr, names[k], origin.x + 1.35 * arm * d.x, origin.y + 1.35 * arm * d.y, 0.5,
                      0.5);
        } else {
            // Seen nearly end on: a dot at the origin when the axis points at the viewer, a ring
            // when away, and its label below left, clear of the others'.
            cairo_new_path(cr);
            cairo_arc(cr, origin.x, origin.y, 0.25 * guide_font(view), 0.0, 2.0 * std::numbers::pi);
            if (dot(axes[k], c.toward) > 0.0) cairo_fill_preserve(cr);
            cairo_stroke(cr);
            draw_text(cr, names[k], origin.x - 0.5 * arm, origin.y + 0.5 * arm, 0.5, 0.5);
        }
    }
}

/// The longest length 1, 2 or 5 × 10^n at most `room`.
double round_length(double room) {
    const double p = std::pow(10.0, std::floor(std::log10(room)));
    for (const double m : {5.0, 2.0}) {
        if (m * p <= room) return m * p;
    }
    return p;
}

/// The scale bar at the bottom right: a round length, with end ticks, labelled above.
void draw_scale_bar(cairo_t* cr, const PageMap& map, const SurfaceView& view) {
    if (!(map.scale > 0.0) || !std::isfinite(map.scale)) return;
    const double length = round_length(scale_bar_fraction * view.width / map.scale);
    if (!(length > 0.0) || !std::isfinite(length)) return;
    const double font = guide_font(view);
    const double right = view.width - margin_size(view);
    const double left = right - length * map.scale;
    const double y = view.height - 0.5 * bottom_size(view) + 0.5 * font;
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    cairo_set_line_width(cr, std::max(1.0, 0.12 * font));
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
    cairo_move_to(cr, left, y - 0.4 * font);
    cairo_line_to(cr, left, y);
    cairo_line_to(cr, right, y);
    cairo_line_to(cr, right, y - 0.4 * font);
    cairo_stroke(cr);
    set_font(cr, font);
    draw_text(cr, typeset(fmt::format("{:g}", length)), 0.5 * (left + right), y - 0.6 * font, 0.5,
              1.0);
}

/// The colour bar in the middle of the band: the map from −max|v| to max|v| left to right,
/// the label above, the ends (and 0) below.
void draw_colorbar(cairo_t* cr, const Scene& sc, const SurfaceView& view) {
    const double font = guide_font(view);
    const double x0 = colorbar_lo * view.width;
    const double x1 = colorbar_hi * view.width;
    const double h = colorbar_thickness * std::min(view.width, view.height);
    const double y = view.height - 0.5 * bottom_size(view) - 0.5 * h;
    cairo_pattern_t* gradient = cairo_pattern_create_linear(x0, 0.0, x1, 0.0);
    const std::span<const Color> map = color_map(true);
    for (std::size_t i = 0; i < map.size(); ++i) {
        cairo_pattern_add_color_stop_rgb(
            gradient, static_cast<double>(i) / static_cast<double>(map.size() - 1), map[i].r,
            map[i].g, map[i].b);
    }
    cairo_rectangle(cr, x0, y, x1 - x0, h);
    cairo_set_source(cr, gradient);
    cairo_fill_preserve(cr);
    cairo_pattern_destroy(gradient);
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    cairo_set_line_width(cr, 0.5);
    cairo_stroke(cr);
    set_font(cr, font);
    draw_text(cr, sc.coloring->label, 0.5 * (x0 + x1), y - 0.3 * font, 0.5, 1.0);
    for (const auto& [v, text] : colorbar_labels(sc.range)) {
        const double x = x0 + sc.range.t(v) * (x1 - x0);
        cairo_move_to(cr, x, y + h);
        cairo_line_to(cr, x, y + h + 0.3 * font);
        cairo_stroke(cr);
        draw_text(cr, text, x, y + h + 0.4 * font, 0.5, 0.0);
    }
}

void draw(cairo_t* cr, std::span<const Surface> surfaces, const PageMap& map,
          const SurfaceView& view, const SurfaceColoring* coloring) {
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_paint(cr);
    const std::vector<Facet> facets = front_facets(surfaces, map.camera);
    const Scene sc = scene(surfaces, map, view, coloring);
    paint(cr, sc, facets, map.camera);
    if (view.guides) {
        draw_triad(cr, map, view);
        draw_scale_bar(cr, map, view);
    }
    if (coloring != nullptr) draw_colorbar(cr, sc, view);
    if (!view.title.empty()) {
        // A title wider than the picture less its margins is set smaller, to fit.
        const double size = title_size(view);
        const double room = view.width - 2.0 * margin_size(view);
        cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
        set_font(cr, size);
        const double width = text_width(cr, view.title);
        if (width > room && room > 0.0) set_font(cr, size * room / width);
        draw_text(cr, view.title, 0.5 * view.width, size, 0.5, 0.5);
    }
}

void check_view(const SurfaceView& view) {
    for (const auto& [size, name] : {std::pair{view.width, "width"}, {view.height, "height"}}) {
        if (size < 1 || size > max_picture_size) {
            throw InvalidInput(fmt::format("surface picture {} must be in [1, {}], got {}", name,
                                           max_picture_size, size));
        }
    }
    if (!std::isfinite(view.azimuth) || !std::isfinite(view.elevation)) {
        throw InvalidInput(
            fmt::format("surface picture azimuth and elevation must be finite, "
                        "got {} and {}",
                        view.azimuth, view.elevation));
    }
}

/// The joint bounding box of the surfaces, after checking their indices and vertices.
Box3 checked_bounding_box(std::span<const Surface> surfaces) {
    Box3 box = Box3::empty();
    for (std::size_t i = 0; i < surfaces.size(); ++i) {
        const Surface& s = surfaces[i];
        for (std::size_t t = 0; t < s.size(); ++t) {
            for (const std::uint32_t v : s.triangles[t]) {
                if (v >= s.vertices.size()) {
                    throw InvalidInput(
                        fmt::format("surface {}: triangle {} has vertex {}, but there are only {}",
                                    i, t, v, s.vertices.size()));
                }
                if (!is_finite(s.vertices[v])) {
                    throw InvalidInput(fmt::format("surface {}: vertex {} is not finite", i, v));
                }
            }
        }
        if (!s.empty()) box = unite(box, bounding_box(s));
    }
    if (box.is_empty()) throw InvalidInput("surface picture: every surface is empty");
    return box;
}

void check_coloring(const Surface& surface, const SurfaceColoring& coloring) {
    if (coloring.values.size() != surface.vertices.size()) {
        throw InvalidInput(fmt::format("surface picture: {} values to colour by, for {} vertices",
                                       coloring.values.size(), surface.vertices.size()));
    }
    for (std::size_t i = 0; i < coloring.values.size(); ++i) {
        if (!std::isfinite(coloring.values[i])) {
            throw InvalidInput(
                fmt::format("surface picture: the value at vertex {} is not finite", i));
        }
    }
}

void save(std::span<const Surface> surfaces, const SurfaceColoring* coloring,
          const std::filesystem::path& path, const SurfaceView& view) {
    const PictureFormat format = picture_format(path);
    check_view(view);
    const PageMap map = page_map(checked_bounding_box(surfaces), view);
    // The page is drawn in pixels (points in SVG); write_picture scales the PNG by png_scale,
    // which the drawing undoes.
    const double unit = format == PictureFormat::png ? 1.0 / png_scale : 1.0;
    write_picture(path, format, unit * view.width, unit * view.height, [&](cairo_t* cr) {
        cairo_scale(cr, unit, unit);
        draw(cr, surfaces, map, view, coloring);
    });
}

/// "+x" for the axis direction nearest the unit vector v (its largest component).
std::string axis_name(Vec3 v) {
    int a = 0;
    for (int i = 1; i < 3; ++i)
        if (std::abs(v[i]) > std::abs(v[a])) a = i;
    return fmt::format("{}{}", v[a] < 0.0 ? '-' : '+', "xyz"[a]);
}

}  // namespace

void save_surface_views(std::span<const Surface> surfaces, const std::filesystem::path& path,
                        const SurfaceView& view) {
    const PictureFormat format = picture_format(path);
    check_view(view);
    SurfaceView page = view;
    page.width *= 2;
    page.height *= 2;
    check_view(page);
    const Box3 box = checked_bounding_box(surfaces);
    std::array<SurfaceView, 4> views{view, view, view, view};
    views[1].azimuth = 0.0;
    views[1].elevation = 0.0;
    views[2].azimuth = 90.0;
    views[2].elevation = 0.0;
    views[3].azimuth = 0.0;
    views[3].elevation = 90.0;
    for (std::size_t i = 1; i < views.size(); ++i)
        views[i].title = "from " + axis_name(camera(views[i]).toward);
    views[3].title += " (above)";
    const double unit = format == PictureFormat::png ? 1.0 / png_scale : 1.0;
    auto at = [&](std::size_t i) {
        return Vec2{static_cast<double>(i % 2) * view.width,
                    static_cast<double>(i / 2) * view.height};
    };
    if (format == PictureFormat::png) {
        // Each view drawn on a thread of its own, into an image of its own pixels (a pixel a
        // unit of the view, as the page's), then the four set on the page: the same picture
        // for any thread count, in a quarter of the time on four cores.
        std::vector<SurfacePtr> images;
        for (std::size_t i = 0; i < views.size(); ++i) {
            images.emplace_back(
                cairo_image_surface_create(CAIRO_FORMAT_RGB24, static_cast<int>(view.width),
                                           static_cast<int>(view.height)),
                &cairo_surface_destroy);
        }
        parallel_for(
            views.size(),
            [&](std::size_t i) {
                const ContextPtr cr(cairo_create(images[i].get()), &cairo_destroy);
                draw(cr.get(), surfaces, page_map(box, views[i]), views[i], nullptr);
                check(cairo_status(cr.get()), path);
            },
            1);
        write_picture(path, format, unit * 2 * view.width, unit * 2 * view.height,
                      [&](cairo_t* cr) {
                          cairo_scale(cr, unit, unit);
                          for (std::size_t i = 0; i < views.size(); ++i) {
                              cairo_set_source_surface(cr, images[i].get(), at(i).x, at(i).y);
                              cairo_paint(cr);
                          }
                      });
        return;
    }
    write_picture(path, format, unit * 2 * view.width, unit * 2 * view.height, [&](cairo_t* cr) {
        cairo_scale(cr, unit, unit);
        for (std::size_t i = 0; i < views.size(); ++i) {
            cairo_save(cr);
            cairo_translate(cr, at(i).x, at(i).y);
            cairo_rectangle(cr, 0.0, 0.0, view.width, view.height);
            cairo_clip(cr);
            draw(cr, surfaces, page_map(box, views[i]), views[i], nullptr);
            cairo_restore(cr);
        }
    });
}

UpAxis up_axis(const Box3& box) {
    const Vec3 e = box.hi - box.lo;
    const double shorter = std::min(e.y, e.z);
    const double longer = std::max(e.y, e.z);
    // A sphere, a cube, or y and z nearly alike: z, the default (also for an empty box or NaN).
    if (!(shorter < alike_extent * longer)) return UpAxis::z;
    // Standing: the longer of y and z is the height, x the width between it and the depth.
    const bool standing = alike_extent * longer > e.x && e.x >= alike_extent * shorter;
    return standing == (e.y > e.z) ? UpAxis::y : UpAxis::z;
}

void save_surface_picture(std::span<const Surface> surfaces, const std::filesystem::path& path,
                          const SurfaceView& view) {
    save(surfaces, nullptr, path, view);
}

void save_surface_picture(const Surface& surface, const std::filesystem::path& path,
                          const SurfaceView& view) {
    save_surface_picture(std::span<const Surface>(&surface, 1), path, view);
}

void save_surface_picture(const Surface& surface, const SurfaceColoring& coloring,
                          const std::filesystem::path& path, const SurfaceView& view) {
    check_coloring(surface, coloring);
    save(std::span<const Surface>(&surface, 1), &coloring, path, view);
}

}  // namespace slc
