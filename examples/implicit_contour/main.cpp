// Contouring a function of your own with the contour module alone: no curve, no distance tree,
// no time loop. The function is a Cassini oval, the points whose distances to the foci (±a, 0)
// multiply to b²:
//     G(x, y) = (x² + y²)² − 2a²(x² − y²) + a⁴ − b⁴,
// negative inside. It is not a distance (|∇G| ranges from 0 at the origin to about 4|x|³), and its
// zero set is two ovals for b < a, one peanut-shaped curve for a < b < a√2, and an oval for larger
// b.
//
// Run:  build/bin/example_implicit_contour [--out DIR]
// Prints the segments of a coarse contour and draws it as the paper's Fig. 5
// (DIR/linear_contour.png: the tree's triangulation, the linear interpolant's zero set, its
// vertices moved along their triangle edges to roots of G), contours three shapes finely, checks
// each vertex against the known zero set |x − F1|·|x − F2| = b² and the number of curves, and
// draws DIR/implicit_contour.svg and .png (default DIR: implicit_contour_out).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <slc/slc.hpp>
#include <string>

namespace {

constexpr double a = 1.0;  // foci at (±a, 0)

double cassini(slc::Vec2 p, double b) {
    const double r2 = p.x * p.x + p.y * p.y;
    return r2 * r2 - 2.0 * a * a * (p.x * p.x - p.y * p.y) + a * a * a * a - b * b * b * b;
}

/// Largest |(|x − F1| |x − F2|) − b²| over the vertices: 0 on the exact zero set.
double zero_set_error(const slc::Interface& curves, double b) {
    double worst = 0.0;
    for (const slc::Vec2 p : curves.points()) {
        const double product = slc::distance(p, {-a, 0.0}) * slc::distance(p, {a, 0.0});
        worst = std::max(worst, std::abs(product - b * b));
    }
    return worst;
}

/// Draws DIR/linear_contour.png (the paper's Fig. 5) for the contour c of g without refinement:
/// (a) the topology tree's triangulation with the sign of G at its vertices and the zero set of
/// the linear interpolant, (b) a closer view where the roots found along the triangle edges sit
/// beside the interpolant's vertices. Returns whether every vertex of c lies on a triangle edge
/// whose ends G gives opposite signs, with |G| ≤ η there.
template <class G>
bool draw_linear_contour(const slc::ContourResult& c, const G& g, const slc::Box& domain,
                         const std::filesystem::path& out) {
    const slc::Triangulation mesh = slc::triangulate(c.tree);
    std::vector<double> value(mesh.vertices.size());
    g(mesh.vertices, value);
    struct Crossing {
        slc::Vec2 a, b, linear;  // the edge's ends, and where the interpolant vanishes on it
    };
    std::vector<Crossing> crossings;
    std::vector<std::vector<slc::Vec2>> linear_segments;
    std::vector<slc::Vec2> inside, outside;
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
        (value[i] < 0.0 ? inside : outside).push_back(mesh.vertices[i]);
    for (const auto& t : mesh.triangles) {
        std::vector<slc::Vec2> ends;
        for (int e = 0; e < 3; ++e) {
            const std::uint32_t i = t[e], j = t[(e + 1) % 3];
            if ((value[i] < 0.0) == (value[j] < 0.0)) continue;
            const double s = value[i] / (value[i] - value[j]);
            const slc::Vec2 x = mesh.vertices[i] + s * (mesh.vertices[j] - mesh.vertices[i]);
            crossings.push_back({mesh.vertices[i], mesh.vertices[j], x});
            ends.push_back(x);
        }
        if (ends.size() == 2) linear_segments.push_back(ends);
    }
    // Each vertex of c on its edge: the arrow from the interpolant's vertex to the root.
    bool all_on_edges = true;
    std::vector<slc::Vec2> from, moved;
    std::vector<double> at_roots(c.curves.size());
    g(c.curves.points(), at_roots);
    for (std::size_t v = 0; v < c.curves.size(); ++v) {
        const slc::Vec2 x = c.curves.point(v);
        const Crossing* on = nullptr;
        for (const Crossing& e : crossings) {
            const double d2 = slc::closest_point(slc::Segment{e.a, e.b}, x).distance2;
            if (std::sqrt(d2) <= 1e-12 * (1.0 + slc::norm(x))) on = &e;
        }
        all_on_edges = all_on_edges && on != nullptr && std::abs(at_roots[v]) <= 1e-10;
        if (on) {
            from.push_back(on->linear);
            moved.push_back(x - on->linear);
        }
    }
    const slc::Color grey{0.7, 0.7, 0.7}, blue{0.2, 0.35, 0.8}, orange{0.95, 0.55, 0.1},
        red{0.85, 0.1, 0.1}, black{0.0, 0.0, 0.0, 1.0};
    std::vector<slc::Figure> panels;
    const slc::Box near{{0.6, -0.1}, {1.5, 0.8}};
    panels.emplace_back(domain, "(a) the interpolant's zero set on the K = 3 tree");
    panels.emplace_back(near, "(b) its vertices moved along their edges to |G| <= eta");
    for (slc::Figure& f : panels) {
        f.add_triangles(mesh.vertices, mesh.triangles, grey, 0.6);
        f.add_points(inside, blue, 2.0);
        f.add_points(outside, orange, 2.0);
        for (std::size_t i = 0; i < linear_segments.size(); ++i) {
            f.add_polyline(linear_segments[i], i == 0 ? "zero set of the linear interpolant" : "",
                           red, 1.2);
        }
        f.add_polyline(std::vector<slc::Vec2>{}, "G < 0 at a vertex", blue, 2.0);
        f.add_polyline(std::vector<slc::Vec2>{}, "G > 0 at a vertex", orange, 2.0);
    }
    panels[1].add_arrows(from, moved, 1.0, black);
    for (slc::Figure& f : panels)
        f.add_curves(c.curves, "the contour: roots of G on the edges", black, 1.0);
    slc::Figure::save_grid(panels, 2, out / "linear_contour.png");
    std::printf("wrote %s\n", (out / "linear_contour.png").c_str());
    return all_on_edges && from.size() == c.curves.size();
}

}  // namespace

int main(int argc, char** argv) try {
    std::filesystem::path out = "implicit_contour_out";
    if (argc == 3 && std::string(argv[1]) == "--out") out = argv[2];
    const slc::Box domain = slc::Box::centered_square(2.0);

    // A coarse contour, printed segment by segment. pointwise() turns a function of one point into
    // the batch function contour() evaluates on all cores.
    const double b_print = 1.2;
    const auto g_print = slc::pointwise([&](slc::Vec2 p) { return cassini(p, b_print); });
    slc::ContourOptions coarse_options;
    coarse_options.depth = 3;  // K: a 2^3 × 2^3 topology tree at most
    const slc::ContourResult coarse = slc::contour(g_print, domain, coarse_options);
    std::printf("b = %.2f, K = 3: %zu curve(s), %zu segments (x0, y0) -> (x1, y1)\n", b_print,
                coarse.curves.curve_count(), coarse.curves.size());
    for (std::size_t i = 0; i < coarse.curves.size(); ++i) {
        const slc::Segment s = coarse.curves.segment(i);
        std::printf("  (%+.6f, %+.6f) -> (%+.6f, %+.6f)\n", s.a.x, s.a.y, s.b.x, s.b.y);
    }

    // The paper's Fig. 5 from this coarse contour: the tree's triangulation, the zero set of the
    // piecewise-linear interpolant of G on it, and each of its vertices moved along its
    // triangle edge to a root of G (|G| ≤ η): every vertex of the contour lies on an edge whose
    // ends G gives opposite signs.
    const bool roots_on_edges = draw_linear_contour(coarse, g_print, domain, out);
    std::printf("every vertex of the coarse contour on a sign-changing triangle edge: %s\n",
                roots_on_edges ? "yes" : "no");

    // Three shapes, finely: K = 6 and refinement to convergence (|G| ≤ ε at every midpoint).
    struct Case {
        double b;
        std::size_t curves;  // the known topology
    };
    const Case cases[] = {{0.98, 2}, {1.2, 1}, {1.6, 1}};
    slc::Figure figure(domain, "Cassini ovals |x - F1| |x - F2| = b^2, a = 1");
    bool ok = true;
    for (std::size_t i = 0; i < std::size(cases); ++i) {
        const double b = cases[i].b;
        const auto g = slc::pointwise([b](slc::Vec2 p) { return cassini(p, b); });
        slc::ContourOptions options;
        options.depth = 6;
        options.refine_passes = slc::ContourOptions::until_converged;
        options.eps = 1e-5;
        const slc::ContourResult c = slc::contour(g, domain, options);
        const double error = zero_set_error(c.curves, b);
        double midpoint_g = 0.0;  // largest |G| at a segment midpoint: the refinement's target
        for (std::size_t j = 0; j < c.curves.size(); ++j) {
            const slc::Segment s = c.curves.segment(j);
            midpoint_g = std::max(midpoint_g, std::abs(cassini(0.5 * (s.a + s.b), b)));
        }
        std::printf(
            "b = %.2f: %zu curve(s) (want %zu), %zu segments, %zu G evaluations, area "
            "%.6f\n    max ||x-F1| |x-F2| - b^2| = %.1e at vertices; max |G| = %.1e at "
            "midpoints (eps %.0e, %zu splits refused)\n",
            b, c.curves.curve_count(), cases[i].curves, c.curves.size(), c.stats.g_evals,
            slc::area(c.curves), error, midpoint_g, *options.eps, c.stats.rejected);
        // G = P² − b⁴ for P = |x − F1| |x − F2|, so |P − b²| = |G| / (P + b²) ≤ η / (2b²) at a
        // vertex, where |G| ≤ η = 1e-10: about 5e-11, plus rounding. Midpoints meet ε unless the
        // refinement's safeguards refused a split.
        ok = ok && c.curves.curve_count() == cases[i].curves && error < 1e-9 &&
             (midpoint_g <= *options.eps || c.stats.rejected > 0) && slc::area(c.curves) > 0.0;
        char label[32];
        std::snprintf(label, sizeof label, "b = %.2f", b);
        figure.add_curves(c.curves, label, slc::palette_color(i));
    }
    figure.save(out / "implicit_contour.svg");
    figure.save(out / "implicit_contour.png");
    std::printf("wrote %s\n", (out / "implicit_contour.png").c_str());
    return ok && roots_on_edges ? 0 : 1;
} catch (const std::exception& e) {
    std::fprintf(stderr, "implicit_contour: %s\n", e.what());
    return 2;
}
