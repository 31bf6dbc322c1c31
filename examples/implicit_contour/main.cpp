// Contouring a function of your own with the contour module alone: no curve, no distance tree,
// no time loop. The function is a Cassini oval, the points whose distances to the foci (±a, 0)
// multiply to b²:
//     G(x, y) = (x² + y²)² − 2a²(x² − y²) + a⁴ − b⁴,
// negative inside. It is not a distance (|∇G| ranges from 0 at the origin to about 4|x|³), and its
// zero set is two ovals for b < a, one peanut-shaped curve for a < b < a√2, and an oval for larger
// b.
//
// Run:  build/bin/example_implicit_contour [--out DIR]
// Prints the segments of a coarse contour, contours three shapes finely, checks each vertex
// against the known zero set |x − F1|·|x − F2| = b² and the number of curves, and draws
// DIR/implicit_contour.svg and .png (default DIR: implicit_contour_out).
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
    return ok ? 0 : 1;
} catch (const std::exception& e) {
    std::fprintf(stderr, "implicit_contour: %s\n", e.what());
    return 2;
}
