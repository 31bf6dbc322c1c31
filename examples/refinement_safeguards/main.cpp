// Refinement's safeguards (paper §2.2, Fig. 8), on two zero sets the linear contour gets wrong.
//
// (a) Topology preservation. The Cassini oval with b just below a is two ovals 0.09 apart:
//     G(x, y) = (x² + y²)² − 2a²(x² − y²) + a⁴ − b⁴,   a = 1, b = 0.999,
// and on the K = 4 tree (no tree vertex in the gap) the linear interpolant bridges the gap: one
// curve where G has two. Refinement moves each new vertex towards the zero set; the safeguards
// refuse the new vertices that would make a tiny angle with, or cross, another segment, so the
// paper's refined contour (ContourOptions::part_bridges off) keeps the interpolant's topology:
// one simple curve. slc's default then parts the bridge where G between its sides is positive:
// the two ovals.
//
// (b) Triangle limiting. A thin ellipse's tips, which the tree's triangles cut off at K = 3. With
// the triangle safeguard (ContourOptions::triangle_safeguard, the paper's), a new vertex stays in
// its segment's triangle or moves to an adjacent one where the interpolant has no segment, so the
// tips stay cut; without it a vertex goes as far as its bracket reaches and refinement follows
// the tips further.
//
// Run:  build/bin/example_refinement_safeguards [--out DIR]
// Prints what each contour did and draws DIR/safeguards.png (the paper's Fig. 8); exits nonzero
// unless the safeguards held (default DIR: refinement_safeguards_out).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <slc/slc.hpp>
#include <string>
#include <vector>

namespace {

constexpr double a = 1.0, b = 0.999;

/// A thin ellipse with semi-axes 0.85 and 0.08 about (0.03, −0.02), turned by 0.3 rad:
/// (u/0.85)² + (v/0.08)² − 1 in its own frame. Its tips, of radius 0.0075, lie within cells of
/// 0.25 at K = 3.
const slc::Vec2 ellipse_centre{0.03, -0.02};
constexpr double tip = 0.85, half_width = 0.08, ellipse_turn = 0.3;

slc::Vec2 ellipse_frame(slc::Vec2 p) {
    const slc::Vec2 d = p - ellipse_centre;
    const double c = std::cos(ellipse_turn), s = std::sin(ellipse_turn);
    return {c * d.x + s * d.y, -s * d.x + c * d.y};
}

double ellipse(slc::Vec2 p) {
    const slc::Vec2 q = ellipse_frame(p);
    return (q.x / tip) * (q.x / tip) + (q.y / half_width) * (q.y / half_width) - 1.0;
}

/// The largest distance from a tip or side of the ellipse (the ends of its axes) to the curves.
double tip_cut(const slc::Interface& curves) {
    double worst = 0.0;
    const double c = std::cos(ellipse_turn), s = std::sin(ellipse_turn);
    for (const slc::Vec2 q : {slc::Vec2{tip, 0}, slc::Vec2{0, half_width}, slc::Vec2{-tip, 0},
                              slc::Vec2{0, -half_width}}) {
        const slc::Vec2 end = ellipse_centre + slc::Vec2{c * q.x - s * q.y, s * q.x + c * q.y};
        double nearest = 1e300;
        for (std::size_t i = 0; i < curves.size(); ++i)
            nearest =
                std::min(nearest, std::sqrt(slc::closest_point(curves.segment(i), end).distance2));
        worst = std::max(worst, nearest);
    }
    return worst;
}

double cassini(slc::Vec2 p) {
    const double r2 = p.x * p.x + p.y * p.y;
    return r2 * r2 - 2.0 * a * a * (p.x * p.x - p.y * p.y) + a * a * a * a - b * b * b * b;
}

/// Where the vertices of a refined contour lie against the tree's triangles: in a triangle the
/// linear interpolant crosses (G changes sign at its corners), in one sharing an edge with such
/// a triangle, or farther.
struct Placement {
    std::size_t crossed = 0, adjacent = 0, farther = 0;
    std::vector<slc::Vec2> farther_points;
};

Placement place(const slc::Interface& curves, const slc::Triangulation& mesh,
                const std::vector<double>& value) {
    const std::size_t n = mesh.triangles.size();
    std::vector<char> crossed(n, 0);
    for (std::size_t t = 0; t < n; ++t) {
        const auto& tri = mesh.triangles[t];
        const bool s0 = value[tri[0]] < 0.0;
        crossed[t] = (value[tri[1]] < 0.0) != s0 || (value[tri[2]] < 0.0) != s0;
    }
    // Triangles beside a crossed one: sharing an edge (two corners).
    std::vector<char> beside(n, 0);
    std::set<std::pair<std::uint32_t, std::uint32_t>> crossed_edges;
    for (std::size_t t = 0; t < n; ++t) {
        if (!crossed[t]) continue;
        const auto& tri = mesh.triangles[t];
        for (int e = 0; e < 3; ++e) crossed_edges.insert(std::minmax(tri[e], tri[(e + 1) % 3]));
    }
    for (std::size_t t = 0; t < n; ++t) {
        const auto& tri = mesh.triangles[t];
        for (int e = 0; e < 3; ++e)
            if (crossed_edges.count(std::minmax(tri[e], tri[(e + 1) % 3]))) beside[t] = 1;
    }
    const auto contains = [&](std::size_t t, slc::Vec2 x) {
        const auto& tri = mesh.triangles[t];
        const slc::Vec2 p = mesh.vertices[tri[0]], q = mesh.vertices[tri[1]],
                        r = mesh.vertices[tri[2]];
        const auto side = [](slc::Vec2 u, slc::Vec2 v, slc::Vec2 w) {
            return (v.x - u.x) * (w.y - u.y) - (v.y - u.y) * (w.x - u.x);
        };
        const double d1 = side(p, q, x), d2 = side(q, r, x), d3 = side(r, p, x);
        const double tol = -1e-14;
        return (d1 >= tol && d2 >= tol && d3 >= tol) || (d1 <= -tol && d2 <= -tol && d3 <= -tol);
    };
    Placement out;
    for (const slc::Vec2 x : curves.points()) {
        int best = 2;  // 0 crossed, 1 beside, 2 farther
        for (std::size_t t = 0; t < n && best > 0; ++t)
            if (contains(t, x)) best = std::min(best, crossed[t] ? 0 : beside[t] ? 1 : 2);
        if (best == 0) ++out.crossed;
        if (best == 1) ++out.adjacent;
        if (best == 2) {
            ++out.farther;
            out.farther_points.push_back(x);
        }
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) try {
    std::filesystem::path out = "refinement_safeguards_out";
    if (argc == 3 && std::string(argv[1]) == "--out") out = argv[2];
    const slc::Color grey{0.75, 0.75, 0.75}, red{0.85, 0.1, 0.1}, black{0.0, 0.0, 0.0, 1.0},
        blue{0.2, 0.35, 0.8}, light{0.6, 0.6, 0.6};
    std::vector<slc::Figure> panels;
    bool ok = true;

    // (a) The Cassini ovals on a domain whose tree has no vertex in the gap (one at the origin
    // would find G > 0 there and part them).
    {
        const slc::Box domain{{-1.93, -1.95}, {2.07, 2.05}};
        const auto g = slc::pointwise(cassini);
        slc::ContourOptions o;
        o.depth = 4;
        const slc::ContourResult linear = slc::contour(g, domain, o);
        o.refine_passes = 3;
        o.eps = 1e-4;
        const slc::ContourResult parted = slc::contour(g, domain, o);
        o.part_bridges = false;  // the paper's refinement
        const slc::ContourResult refined = slc::contour(g, domain, o);
        slc::ContourOptions fine = o;
        fine.depth = 8;
        fine.refine_passes = slc::ContourOptions::until_converged;
        fine.eps = 1e-8;
        const slc::ContourResult truth = slc::contour(g, domain, fine);
        const bool simple = !slc::find_crossing(refined.curves).has_value();
        std::printf(
            "(a) zero set of G: %zu curves; linear contour at K = 4: %zu; refined (3 passes, eps "
            "1e-4): %zu, %s, %zu splits refused; with the bridge parted (the default): %zu\n",
            truth.curves.curve_count(), linear.curves.curve_count(), refined.curves.curve_count(),
            simple ? "simple" : "NOT simple", refined.stats.rejected, parted.curves.curve_count());
        ok = ok && truth.curves.curve_count() == 2 && linear.curves.curve_count() == 1 &&
             refined.curves.curve_count() == 1 && simple && refined.stats.rejected > 0 &&
             parted.curves.curve_count() == 2 && parted.stats.parted == 1 &&
             !slc::find_crossing(parted.curves).has_value();
        const slc::Triangulation mesh = slc::triangulate(linear.tree);
        panels.emplace_back(slc::Box{{-0.5, -0.45}, {0.5, 0.45}},
                            "(a) topology preservation: the bridge of the K = 4 contour is kept");
        slc::Figure& f = panels.back();
        f.add_triangles(mesh.vertices, mesh.triangles, grey, 0.6);
        f.add_curves(truth.curves, "zero set of G (two ovals)", light, 3.0);
        f.add_curves(linear.curves, "linear contour", red, 1.0);
        f.add_curves(refined.curves, "refined, 3 passes: one simple curve", black, 1.2);
        f.add_points(refined.curves.points(), black, 2.0);
    }

    // (b) The ellipse at K = 3, refined with and without the triangle safeguard.
    {
        const slc::Box domain = slc::Box::centered_square(2.0);
        const auto g = slc::pointwise(ellipse);
        slc::ContourOptions o;
        o.depth = 3;
        const slc::ContourResult linear = slc::contour(g, domain, o);
        const slc::Triangulation mesh = slc::triangulate(linear.tree);
        std::vector<double> value(mesh.vertices.size());
        g(mesh.vertices, value);
        o.eps = 1e-4;
        o.refine_passes = slc::ContourOptions::until_converged;
        std::printf("(b) the ellipse's linear contour at K = 3: tips cut by %.3g\n",
                    tip_cut(linear.curves));
        panels.emplace_back(slc::Box{{-0.95, -0.95}, {0.95, 0.95}},
                            "(b) triangle limiting: a thin ellipse's tips at K = 3");
        slc::Figure& f = panels.back();
        f.add_triangles(mesh.vertices, mesh.triangles, grey, 0.6);
        f.add_curves(linear.curves, "linear contour", red, 1.0);
        double cut[2] = {0.0, 0.0};
        for (const bool safeguard : {true, false}) {
            o.triangle_safeguard = safeguard;
            const slc::ContourResult r = slc::contour(g, domain, o);
            const Placement p = place(r.curves, mesh, value);
            cut[safeguard ? 0 : 1] = tip_cut(r.curves);
            std::printf(
                "    refined to eps 1e-4, triangle safeguard %s: %zu segments, %zu splits "
                "refused, tips cut by %.3g; vertices in a triangle the linear contour crosses "
                "%zu, beside one %zu, farther %zu\n",
                safeguard ? "on (the paper's)" : "off", r.curves.size(), r.stats.rejected,
                cut[safeguard ? 0 : 1], p.crossed, p.adjacent, p.farther);
            ok = ok && r.curves.curve_count() == 1 && !slc::find_crossing(r.curves);
            if (safeguard) ok = ok && p.farther == 0;
            f.add_curves(r.curves, safeguard ? "refined, triangle safeguard on" : "refined, off",
                         safeguard ? black : blue, 1.2);
            f.add_points(safeguard ? r.curves.points() : p.farther_points, safeguard ? black : blue,
                         safeguard ? 2.0 : 3.0);
        }
        f.add_polyline(std::vector<slc::Vec2>{}, "off: a vertex beyond the triangles beside", blue,
                       3.0);
        // Without the safeguard refinement follows the tips the triangles cut off further.
        ok = ok && cut[1] < 0.5 * cut[0];
    }

    std::filesystem::create_directories(out);
    slc::Figure::save_grid(panels, 2, out / "safeguards.png");
    std::printf("wrote %s\n", (out / "safeguards.png").c_str());
    return ok ? 0 : 1;
} catch (const std::exception& e) {
    std::fprintf(stderr, "refinement_safeguards: %s\n", e.what());
    return 2;
}
