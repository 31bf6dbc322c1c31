// Your own velocity law moving your own curve, with pictures of the motion.
//
// The law is a normal speed that depends on the position and on the normal angle θ
// (N = (cos θ, sin θ)): growth that is faster to the right, and faster sideways than up and down,
//     v(x, θ) = (1 + x/4) (1 + 0.3 cos 2θ),
// written below as a local law in a few lines. The curve is a bean-shaped polygon given as points,
// or the interface file (JSON, see README.md) named on the command line.
//
// Run:  build/bin/example_custom_velocity [shape.json] [--out DIR]
// Writes DIR/custom_velocity.svg and .png (default DIR: custom_velocity_out), and checks the
// result against the comparison principle: with v between v_lo and v_hi, the front at time t lies
// between the level sets v_lo·t and v_hi·t of the initial curve's signed distance.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <slc/slc.hpp>
#include <string>
#include <vector>

namespace {

// ---- the velocity law: the only part specific to this motion ----------------------------------
double speed(slc::Vec2 x, double theta) {
    return (1.0 + 0.25 * x.x) * (1.0 + 0.3 * std::cos(2.0 * theta));
}

std::unique_ptr<slc::VelocityLaw> sideways_growth() {
    // Asks for vertex normals (intrinsic module, paper Eqs. 7-8); returns u = v N, points moving
    // with dy/dt = u, so v > 0 moves the curve outward.
    return slc::local_law("sideways-growth", {.normals = true},
                          [](double, const slc::VertexState& s) {
                              const double theta = std::atan2(s.normal.y, s.normal.x);
                              return speed(s.point, theta) * s.normal;
                          });
}
// -----------------------------------------------------------------------------------------------

/// A bean: counterclockwise around its inside, the closing segment implicit.
std::vector<std::vector<slc::Vec2>> bean() {
    return {{{-1.0, -0.4},
             {-0.3, -0.7},
             {0.4, -0.6},
             {1.0, -0.3},
             {1.1, 0.3},
             {0.7, 0.6},
             {0.2, 0.3},
             {-0.3, 0.4},
             {-0.9, 0.5},
             {-1.2, 0.1}}};
}

}  // namespace

int main(int argc, char** argv) try {
    std::filesystem::path out = "custom_velocity_out";
    std::vector<std::vector<slc::Vec2>> raw = bean();
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--out" && i + 1 < argc) {
            out = argv[++i];
        } else {
            raw = slc::read_interface_json(arg).curves;
        }
    }
    // Checks the curves (closed, simple, finite) and orients them counterclockwise.
    const slc::Interface initial = slc::prepare_interface(raw).curves;
    const double t_end = 0.5;
    const slc::Box box = slc::bounding_box(initial.points());
    const slc::Box domain =
        slc::Box::square(box.center(), 0.5 * std::max(box.width(), box.height()) + 1.5);

    slc::RunOptions options;
    options.t_end = t_end;
    options.steps = 25;
    // K = 6 and no refinement (P = 0, the default): the intrinsic normals of many short refined
    // segments are noisy, and a speed that depends on the normal angle turns that noise into
    // visible wiggles within a few steps.
    options.step.contour.depth = 6;
    std::vector<slc::Interface> frames = {initial};
    const auto law = sideways_growth();
    const slc::RunResult r =
        slc::run(initial, *law, domain, options, [&](const slc::StepReport& s) {
            if (s.step % 5 == 0) frames.push_back(*s.curves);
            return true;
        });
    if (r.status != slc::RunStatus::ok) {
        std::fprintf(stderr, "run ended with %s: %s\n", slc::to_string(r.status),
                     r.message.c_str());
        return 1;
    }

    // Pictures: the frames in a sequential colour map, and the law's velocities on the initial
    // curve as arrows.
    slc::Figure figure(domain, "v = (1 + x/4)(1 + 0.3 cos 2 theta), t = 0 to 0.5");
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const double t = t_end * static_cast<double>(i) / static_cast<double>(frames.size() - 1);
        char label[32];
        std::snprintf(label, sizeof label, "t = %.2f", t);
        figure.add_curves(frames[i], label, slc::sequence_color(t / t_end));
    }
    const std::vector<slc::Vec2> u = slc::vertex_velocities(*law, 0.0, initial);
    figure.add_arrows(initial.points(), u, 0.25, {0.8, 0.1, 0.1, 1.0});
    figure.save(out / "custom_velocity.svg");
    figure.save(out / "custom_velocity.png");

    // Comparison principle: every point of the front has moved outward by a distance between
    // v_lo·t and v_hi·t, the speed bounds over the region swept (inside the final bounding box).
    const slc::Box swept = slc::bounding_box(r.curves.points());
    const double v_lo = (1.0 + 0.25 * swept.lo.x) * 0.7;
    const double v_hi = (1.0 + 0.25 * swept.hi.x) * 1.3;
    const slc::DistanceTree tree(initial, domain, {.depth = 10, .triangulate = false});
    const std::vector<double> d = tree.signed_distances(r.curves.points());
    const double d_min = *std::min_element(d.begin(), d.end());
    const double d_max = *std::max_element(d.begin(), d.end());
    // The contour's own error, about the cell size of the K = 6 tree over the domain, bounds how
    // far outside [v_lo t, v_hi t] a vertex may be.
    const double tolerance = domain.width() / 64.0;
    std::printf("area %.4f -> %.4f, length %.4f -> %.4f, %zu vertices\n", slc::area(initial),
                slc::area(r.curves), slc::length(initial), slc::length(r.curves), r.curves.size());
    std::printf("moved outward by %.4f to %.4f; speed bounds give %.4f to %.4f\n", d_min, d_max,
                v_lo * t_end, v_hi * t_end);
    std::printf("wrote %s\n", (out / "custom_velocity.png").c_str());
    const bool ok = d_min >= v_lo * t_end - tolerance && d_max <= v_hi * t_end + tolerance &&
                    slc::area(r.curves) > slc::area(initial);
    return ok ? 0 : 1;
} catch (const std::exception& e) {
    std::fprintf(stderr, "custom_velocity: %s\n", e.what());
    return 2;
}
