// One step of semi-Lagrangian contouring written out by hand with the library's parts (paper
// §4.3, Fig. 11): the distance tree of Γ(t), the nearest-point extension W of the vertex
// velocities, the predictor's contour of G̃(x) = F(x − k W(x, t)) and the corrector's contour of
// G(x) = F(x − k W̄(x)), W̄(x) = ½ W(x − k W(x, t), t) + ½ W̃(x, t + k), W̃ the extension from the
// predicted curve Γ̃. The same step as slc::advance takes it with the nearest-point extension,
// chords and no area correction: the program checks that the two agree.
//
// The curve is a smooth non-convex blob; the law a rotation about the origin (a flow field, here
// extended from the curve as the paper does, so that W differs from the field off the curve).
//
// Run:  build/bin/example_semi_lagrangian [--out DIR]
// Prints the two steps' largest vertex distance and draws DIR/semi_lagrangian.png (and .svg): the
// predictor's and the corrector's values at a few points, as the paper's Fig. 11 shows them.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <slc/slc.hpp>
#include <string>
#include <vector>

namespace {

using slc::Vec2;

/// The blob r(θ) = 0.55 (1 + 0.25 cos 2θ + 0.1 sin 3θ), n vertices counterclockwise.
slc::Interface blob(int n) {
    std::vector<Vec2> p;
    for (int i = 0; i < n; ++i) {
        const double t = 2.0 * std::numbers::pi * i / n;
        const double r = 0.55 * (1.0 + 0.25 * std::cos(2.0 * t) + 0.1 * std::sin(3.0 * t));
        p.push_back({r * std::cos(t), r * std::sin(t)});
    }
    return slc::Interface({p});
}

/// The state of the interface at one time: its distance tree and its vertex velocities.
struct Level {
    slc::DistanceTree tree;
    std::vector<Vec2> u;
    Level(const slc::Interface& curves, const slc::Box& domain, int depth,
          const slc::VelocityLaw& law, double t)
        : tree(curves, domain, {.depth = depth}), u(slc::vertex_velocities(law, t, curves)) {}
    /// The nearest-point extension W at x, and the nearest point it was read at.
    std::pair<Vec2, slc::ClosestPoint> extension(Vec2 x) const {
        const slc::ClosestPoint p = tree.closest_point(x);
        return {slc::nearest_point_extension<Vec2>(tree.curves(), u, p), p};
    }
    double distance(Vec2 x) const { return tree.closest_point(x).distance; }
};

/// The largest distance from a vertex of a to the polygon b, and back.
double hausdorff(const slc::Interface& a, const slc::Interface& b, const slc::Box& domain) {
    const slc::DistanceTree ta(a, domain, {.depth = 6}), tb(b, domain, {.depth = 6});
    double worst = 0.0;
    for (const Vec2 x : a.points()) worst = std::max(worst, std::abs(tb.closest_point(x).distance));
    for (const Vec2 x : b.points()) worst = std::max(worst, std::abs(ta.closest_point(x).distance));
    return worst;
}

}  // namespace

int main(int argc, char** argv) try {
    std::filesystem::path out = "semi_lagrangian_out";
    if (argc == 3 && std::string(argv[1]) == "--out") out = argv[2];
    const slc::Box domain = slc::Box::centered_square(1.0);
    const slc::Interface curves = blob(128);
    const auto law = slc::make_velocity("rotation", {});  // u(x) = (−y, x)
    const double t = 0.0, k = 0.3;
    const slc::ContourOptions contour{.depth = 6, .refine_passes = 2};
    const int tree_depth = 7;  // L = K + ⌊P/2⌋, as the step takes it

    // Predictor: G̃(x) = F(x − k W(x, t); Γ(t)), contoured to Γ̃.
    const Level now(curves, domain, tree_depth, *law, t);
    const auto predictor =
        slc::pointwise([&](Vec2 x) { return now.distance(x - k * now.extension(x).first); });
    const slc::Interface predicted = slc::contour(predictor, domain, contour).curves;
    // Corrector: G(x) = F(x − k W̄(x); Γ(t)), W̄ the trapezoidal rule's mean of W at the foot at t
    // and of W̃ (from Γ̃) at x at t + k.
    const Level next(predicted, domain, tree_depth, *law, t + k);
    const auto mean_velocity = [&](Vec2 x) {
        const Vec2 foot = x - k * now.extension(x).first;
        return 0.5 * (now.extension(foot).first + next.extension(x).first);
    };
    const auto corrector =
        slc::pointwise([&](Vec2 x) { return now.distance(x - k * mean_velocity(x)); });
    const slc::Interface by_hand = slc::contour(corrector, domain, contour).curves;

    // The library's step with the same choices.
    slc::StepOptions options;
    options.contour = contour;
    options.extension = slc::Extension::nearest_point;
    options.arcs = false;
    options.area_correction = false;
    const slc::Interface stepped = slc::advance(curves, t, k, *law, domain, options).curves;
    const double apart = hausdorff(by_hand, stepped, domain);
    std::printf("one step of k = %g: %zu vertices by hand, %zu by slc::advance, %.3g apart\n", k,
                by_hand.size(), stepped.size(), apart);

    // Fig. 11: at a few points x, what each contour reads.
    std::vector<Vec2> xs;
    for (std::size_t i = 0; i < predicted.size(); i += predicted.size() / 6)
        xs.push_back(predicted.point(i));
    xs.push_back({0.75, 0.55});  // off the curves: G̃(x) > 0
    const slc::Box view = slc::Box::square({0.05, 0.0}, 0.8);
    const slc::Color grey{0.55, 0.55, 0.55}, green{0.1, 0.6, 0.2}, magenta{0.8, 0.1, 0.6},
        purple{0.45, 0.2, 0.8};
    std::vector<slc::Figure> panels;
    panels.emplace_back(view, "(a) predictor: G̃(x) = F(x − k W(x, t))");
    panels.emplace_back(view, "(b) corrector: G(x) = F(x − k W̄(x))");
    panels[0].add_curves(curves, "Γ(t)", slc::palette_color(0), 1.4);
    panels[0].add_curves(predicted, "the predicted curve: the predictor's zero set",
                         slc::palette_color(1), 1.4);
    panels[1].add_curves(curves, "Γ(t)", slc::palette_color(0), 1.4);
    panels[1].add_curves(predicted, "the predicted curve", slc::palette_color(1), 0.8);
    panels[1].add_curves(stepped, "Γ(t + k), G = 0", slc::palette_color(2), 1.4);
    for (std::size_t i = 0; i < xs.size(); ++i) {
        const Vec2 x = xs[i];
        const bool first = i == 0;
        // (a): x's nearest point y on Γ(t) gives W(x) = u(y); the foot x − kW lands at distance
        // |G̃(x)| from its own nearest point ỹ.
        const auto [w, y] = now.extension(x);
        const Vec2 foot = x - k * w;
        const Vec2 landed = now.tree.closest_point(foot).point;
        panels[0].add_polyline(std::vector<Vec2>{x, y.point},
                               first ? "x to its nearest point y: W(x) = u(y)" : "", grey, 0.8);
        panels[0].add_arrows(std::vector<Vec2>{x}, std::vector<Vec2>{-k * w}, 1.0, green);
        panels[0].add_polyline(
            std::vector<Vec2>{foot, landed},
            first ? "the foot to its nearest point: the predictor's |value|" : "", magenta, 1.2);
        // (b): the mean of W at the predictor's foot and W̃ at x sends x to the corrector's foot.
        const Vec2 w_bar = mean_velocity(x);
        panels[1].add_arrows(std::vector<Vec2>{x}, std::vector<Vec2>{-k * w}, 1.0, green);
        panels[1].add_arrows(std::vector<Vec2>{x}, std::vector<Vec2>{-k * w_bar}, 1.0, purple);
        if (first) {
            panels[0].add_polyline(std::vector<Vec2>{}, "x to its foot x − kW(x, t)", green, 1.0);
            panels[1].add_polyline(std::vector<Vec2>{}, "x to the predictor's foot", green, 1.0);
            panels[1].add_polyline(std::vector<Vec2>{}, "x to the corrector's foot", purple, 1.0);
        }
    }
    for (slc::Figure& panel : panels) panel.add_points(xs, {0, 0, 0, 1}, 2.5);
    std::filesystem::create_directories(out);
    slc::Figure::save_grid(panels, 2, out / "semi_lagrangian.png");
    slc::Figure::save_grid(panels, 2, out / "semi_lagrangian.svg");
    std::printf("wrote %s\n", (out / "semi_lagrangian.png").string().c_str());

    // The step by hand is the library's: the same contours to within the bisection's tolerance.
    const double tolerance = 100.0 * contour.resolved_eta();
    if (by_hand.size() != stepped.size() || !(apart <= tolerance)) {
        std::fprintf(stderr,
                     "the step by hand is not slc::advance's (%.3g apart, tolerance %.3g)\n", apart,
                     tolerance);
        return 1;
    }
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
}
