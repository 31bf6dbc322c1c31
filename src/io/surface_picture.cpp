// Shaded pictures of closed triangle surfaces drawn with cairo: an orthographic camera from an
// azimuth and an elevation, back faces culled, the front faces painted far to near by the depth
// of their centroids (the painter's algorithm) in flat Lambert shading, written atomically as
// PNG or SVG through render.cpp's output.
#include "slc/io/surface_picture.hpp"

#include <cairo.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "render_layout.hpp"
#include "slc/core/box3.hpp"
#include "slc/core/error.hpp"
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
/// Each face is also stroked in its own colour this wide (pixels), over the hairline cracks that
/// antialiasing leaves between neighbours (the background shows through at every shared edge
/// where two partly covering triangles are composited one over the other).
constexpr double seam_width = 1.0;
/// Edges, when drawn, are this wide (pixels) and this fraction of the face's brightness.
constexpr double edge_width = 0.6;
constexpr double edge_brightness = 0.55;
/// Surfaces with more triangles than this are drawn without edges: the edges would cover them.
constexpr std::size_t max_edged_triangles = 20000;

/// The camera's orthonormal frame: the picture's right and up, and the direction toward the
/// viewer (right × up = toward); and the unit direction toward the light.
struct Camera {
    Vec3 right;
    Vec3 up;
    Vec3 toward;
    Vec3 light;
};

Vec3 unit(Vec3 v) { return v / norm(v); }

Camera camera(const SurfaceView& view) {
    const double a = view.azimuth * std::numbers::pi / 180.0;
    const double e = view.elevation * std::numbers::pi / 180.0;
    Camera c;
    c.toward = {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
    c.right = {-std::sin(a), std::cos(a), 0.0};
    c.up = cross(c.toward, c.right);  // +z up unless seen from straight above or below
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
    const double room_y = std::max(view.height - top - margin, 1.0);
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
/// whether their edges are drawn.
struct Scene {
    std::span<const Surface> surfaces;
    std::vector<std::vector<Vec2>> page;  // per surface, per vertex
    std::vector<Color> colors;
    std::vector<bool> edged;
};

Scene scene(std::span<const Surface> surfaces, const PageMap& map, const SurfaceView& view) {
    Scene sc{surfaces, {}, {}, {}};
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

/// Paints the faces in order: each filled and stroked in its shade (or stroked with its edge),
/// the fill left out when the stroke covers the whole face anyway (in-radius below half the
/// stroke's width), as it does for most faces of a fine mesh.
void paint(cairo_t* cr, const Scene& sc, std::span<const Facet> facets, const Camera& camera) {
    // Bevelled joins: a mitred join at a sliver's sharp corner would stick out far beyond it.
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_BEVEL);
    for (const Facet& f : facets) {
        const Surface& s = sc.surfaces[f.surface];
        const TriangleIndices& tri = s.triangles[f.triangle];
        const std::vector<Vec2>& page = sc.page[f.surface];
        const std::array<Vec2, 3> p = {page[tri[0]], page[tri[1]], page[tri[2]]};
        cairo_move_to(cr, p[0].x, p[0].y);
        cairo_line_to(cr, p[1].x, p[1].y);
        cairo_line_to(cr, p[2].x, p[2].y);
        cairo_close_path(cr);

        const Triangle3 t = s.triangle(f.triangle);
        const double shade = brightness(cross(t.b - t.a, t.c - t.a), camera);
        const bool edged = sc.edged[f.surface];
        const double width = edged ? edge_width : seam_width;
        const double twice_area = std::abs(cross(p[1] - p[0], p[2] - p[0]));
        const double perimeter = norm(p[1] - p[0]) + norm(p[2] - p[1]) + norm(p[0] - p[2]);
        set_rgb(cr, sc.colors[f.surface], shade);
        if (2.0 * twice_area >= width * perimeter) cairo_fill_preserve(cr);
        if (edged) set_rgb(cr, sc.colors[f.surface], edge_brightness * shade);
        cairo_set_line_width(cr, width);
        cairo_stroke(cr);
    }
}

void draw(cairo_t* cr, std::span<const Surface> surfaces, const PageMap& map,
          const SurfaceView& view) {
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_paint(cr);
    const std::vector<Facet> facets = front_facets(surfaces, map.camera);
    paint(cr, scene(surfaces, map, view), facets, map.camera);
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

}  // namespace

void save_surface_picture(std::span<const Surface> surfaces, const std::filesystem::path& path,
                          const SurfaceView& view) {
    const PictureFormat format = picture_format(path);
    check_view(view);
    const PageMap map = page_map(checked_bounding_box(surfaces), view);
    // The page is drawn in pixels (points in SVG); write_picture scales the PNG by png_scale,
    // which the drawing undoes.
    const double unit = format == PictureFormat::png ? 1.0 / png_scale : 1.0;
    write_picture(path, format, unit * view.width, unit * view.height, [&](cairo_t* cr) {
        cairo_scale(cr, unit, unit);
        draw(cr, surfaces, map, view);
    });
}

void save_surface_picture(const Surface& surface, const std::filesystem::path& path,
                          const SurfaceView& view) {
    save_surface_picture(std::span<const Surface>(&surface, 1), path, view);
}

}  // namespace slc
