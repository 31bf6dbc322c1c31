// Speed per step against the paper and against the step's floor, scaling with the number of
// segments, the speed-up from threads, and runs beside the programs users would pick instead.
// Writes docs/performance.md itself.
//
// For every cell of Tables 5-7 it runs the first steps (at most --prefix, same k as the full run)
// on one thread and on all threads, then measures, on the interface reached, one step against its
// floor: building the two distance trees, the vertex velocities of both curves, and three G
// evaluations per output vertex of each contour (at the new curve's vertices, midpoints and
// quarter points). Errors and G evaluations per vertex come from the studies that scripts/bench
// runs first (out/study/<problem>/table.json); results do not depend on the thread count.
//
// Every cell is timed in --rounds rounds (default 2), all cells once per round, and each time is
// the least over the rounds, so that a slower spell of a shared machine slows at most one round.
//
// Usage: performance_bench [--out FILE] [--study DIR] [--reference CSV] [--rows n] [--prefix n]
//                          [--rounds n] [--max-segments n]
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <set>
#include <span>
#include <sstream>
#include <thread>

#include "bench_support.hpp"
#include "slc/slc.hpp"

namespace {

using namespace slc;

/// CPU seconds of the calling thread. On one thread it does all of a step's work; the process
/// clock would also count the idle workers of the previous run on all threads, which spin for
/// milliseconds before they sleep.
double cpu_now() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

using slc::bench::wall_now;

/// Least CPU and wall seconds of repeated calls of f: three calls, then more until `seconds` of
/// wall time have passed (at most max_calls), so that neither an interruption of the machine nor
/// the warming up of caches and clock decides a measurement of a small cell.
struct Least {
    double cpu = std::numeric_limits<double>::infinity();
    double wall = std::numeric_limits<double>::infinity();
};
Least least_of_repeats(const std::function<void()>& f, double seconds = 0.5, int max_calls = 50) {
    Least least;
    const double start = wall_now();
    for (int i = 0; i < max_calls && (i < 3 || wall_now() - start < seconds); ++i) {
        const double c0 = cpu_now(), w0 = wall_now();
        f();
        least.cpu = std::min(least.cpu, cpu_now() - c0);
        least.wall = std::min(least.wall, wall_now() - w0);
    }
    return least;
}

/// Least CPU seconds of calls of f: three, then more until a fifth of a second of wall time has
/// passed (at most a hundred).
double best_cpu(const std::function<void()>& f) { return least_of_repeats(f, 0.2, 100).cpu; }

struct PaperCell {
    double e_inf = 0.0;
    double t_step = 0.0;
};

/// The paper's (E_inf, T per step) by table, N and P.
std::map<std::tuple<std::string, int, int>, PaperCell> read_reference(const std::string& path) {
    std::map<std::tuple<std::string, int, int>, PaperCell> out;
    std::istringstream in(read_text_file(path));
    std::string line;
    std::getline(in, line);  // header: table,N,S,K,eps,P,E_inf,T_cpu_s_per_step
    while (std::getline(in, line)) {
        std::vector<std::string> f;
        std::stringstream fields(line);
        for (std::string x; std::getline(fields, x, ',');) f.push_back(x);
        if (f.size() < 8) continue;
        out[{f[0], std::stoi(f[1]), std::stoi(f[5])}] = {std::stod(f[6]), std::stod(f[7])};
    }
    return out;
}

/// A study's cells by (row from 1, P).
using StudyCells = std::map<std::pair<int, int>, nlohmann::json>;

/// Our study cells (error, G evaluations per vertex) by (row, P), when the study has been run.
StudyCells read_study(const std::string& path) {
    StudyCells out;
    std::ifstream in(path);
    if (!in) return out;
    const auto j = nlohmann::json::parse(in);
    for (const auto& c : j.at("cells")) out[{c.at("row").get<int>(), c.at("P").get<int>()}] = c;
    return out;
}

/// One step from `curves` at t against its floor, on one thread.
struct StepFloor {
    double step_s = 0.0;
    double trees_s = 0.0;
    double velocities_s = 0.0;
    double g_s = 0.0;
    double floor_s() const { return trees_s + velocities_s + g_s; }
};

StepFloor measure_floor(const Interface& curves, double t, double k, const VelocityLaw& law,
                        const Box& domain, const StepOptions& options) {
    set_thread_count(1);
    StepFloor f;
    StepResult r;
    f.step_s = best_cpu([&] { r = advance(curves, t, k, law, domain, options); });
    const Interface& next = r.curves;  // stands in for the predicted curve: the same size
    if (next.empty()) return f;
    const DistanceTree::Options tree_options{.depth = options.resolved_tree_depth(),
                                             .triangulate = false};
    std::optional<DistanceTree> now_tree, later_tree;  // the last timed pair, used below
    f.trees_s = best_cpu([&] {
        now_tree.emplace(curves, domain, tree_options);
        later_tree.emplace(next, domain, tree_options);
    });
    const DistanceTree &now = *now_tree, &later = *later_tree;
    std::vector<Vec2> u_now, u_later;
    f.velocities_s = best_cpu([&] {
        u_now = vertex_velocities(law, t, curves, GeometryContext{&now, options.embedded});
        u_later = vertex_velocities(law, t + k, next, GeometryContext{&later, options.embedded});
    });
    // Three points per output vertex: the vertex, and the quarter and half points of its segment.
    std::vector<Vec2> points;
    for (std::size_t i = 0; i < next.size(); ++i) {
        const Segment s = next.segment(i);
        for (double along : {0.0, 0.25, 0.5}) points.push_back(s.a + along * (s.b - s.a));
    }
    const std::span<const Vec2> u0(u_now), u1(u_later);
    auto w_now = [&](Vec2 x) {
        return nearest_point_extension<Vec2>(curves, u0, now.nearest_point(x));
    };
    auto predictor = [&](Vec2 x) { return now.closest_point(x - k * w_now(x)).distance; };
    auto corrector = [&](Vec2 x) {
        const Vec2 foot = x - k * w_now(x);
        const Vec2 w_next = nearest_point_extension<Vec2>(next, u1, later.nearest_point(x));
        return now.closest_point(x - (0.5 * k) * (w_now(foot) + w_next)).distance;
    };
    double sink = 0.0;
    f.g_s = best_cpu([&] {
        for (Vec2 x : points) sink += predictor(x) + corrector(x);
    });
    if (!std::isfinite(sink)) f.g_s = std::numeric_limits<double>::quiet_NaN();
    return f;
}

std::string sci(double v) { return std::isfinite(v) ? fmt::format("{:.3g}", v) : "–"; }

struct TableSpec {
    const char* table;    ///< reference CSV name
    const char* problem;  ///< slc problem
    const char* title;
};

struct Totals {
    std::vector<double> ratios, floors, speedups, evals;
    /// The speed-up on all cores of each cell: (problem, row from 0, P).
    std::map<std::tuple<std::string, int, int>, double> speedup_of;
    std::vector<double> paper_over_floor;  ///< the ratio a step costing only its floor would reach
};

/// One cell's timings, each the least over the rounds that measured it.
struct CellTimes {
    double t_first = std::numeric_limits<double>::infinity();   ///< CPU s per step, first steps
    double wall_one = std::numeric_limits<double>::infinity();  ///< wall s of those, one thread
    double wall_all = std::numeric_limits<double>::infinity();  ///< and on all threads
    double t_step = std::numeric_limits<double>::infinity();    ///< CPU s per step, whole run
    StepFloor floor{
        std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
        std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};

    void lower(const CellTimes& o) {
        t_first = std::min(t_first, o.t_first);
        wall_one = std::min(wall_one, o.wall_one);
        wall_all = std::min(wall_all, o.wall_all);
        t_step = std::min(t_step, o.t_step);
        floor.step_s = std::min(floor.step_s, o.floor.step_s);
        floor.trees_s = std::min(floor.trees_s, o.floor.trees_s);
        floor.velocities_s = std::min(floor.velocities_s, o.floor.velocities_s);
        floor.g_s = std::min(floor.g_s, o.floor.g_s);
    }
};

/// The study's (error, G evaluations per vertex, CPU s per step) of a cell, NaN where missing.
std::tuple<double, double, double> study_cell(const StudyCells& ours, int row, int p) {
    const auto it = ours.find({row + 1, p});
    double e = NAN, evals = NAN, t_study = NAN;
    if (it != ours.end()) {
        if (it->second.at("e_inf").is_number()) e = it->second.at("e_inf").get<double>();
        evals = it->second.at("g_evals_per_vertex").get<double>();
        if (it->second.at("cpu_s_per_step").is_number())
            t_study = it->second.at("cpu_s_per_step").get<double>();
    }
    return {e, evals, t_study};
}

/// Times every cell of one table once (round 0 first), lowering times[cell] (row-major, five
/// values of P per row). The paper's T is the whole run's, and so is ours: a run expected to take
/// under a second is timed here, the least of repeated runs (one run of a few milliseconds also
/// pays the process's first page faults); a longer one is the study's own run in round 0, and
/// one more run in each later round.
void time_cells(const TableSpec& spec, int rows, int prefix, const StudyCells& ours, int round,
                std::vector<CellTimes>& times) {
    const Problem problem = make_problem(spec.problem);
    const auto law = make_velocity(problem.velocity, problem.velocity_params, problem.module);
    const Interface initial = prepare_interface(problem.initial, problem.domain).curves;
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    times.resize(static_cast<std::size_t>(rows) * 5);
    for (int row = 0; row < rows; ++row) {
        for (int p = 0; p < 5; ++p) {
            const RunOptions full = study_cell_options(problem, row, p, RunOptions{});
            RunOptions o = full;
            o.steps = std::min(full.steps, prefix);
            o.t_end = full.t_start + (full.t_end - full.t_start) * o.steps / full.steps;
            CellTimes now;
            RunResult one;
            set_thread_count(1);
            const Least on_one =
                least_of_repeats([&] { one = run(initial, *law, problem.domain, o); });
            set_thread_count(static_cast<int>(cores));
            const Least on_all =
                least_of_repeats([&] { (void)run(initial, *law, problem.domain, o); });
            now.t_first = on_one.cpu / std::max(1, one.steps_done);
            now.wall_one = on_one.wall;
            now.wall_all = on_all.wall;
            const double k = (full.t_end - full.t_start) / full.steps;
            if (!one.curves.empty())
                now.floor = measure_floor(one.curves, one.t, k, *law, problem.domain, o.step);
            const double t_study = std::get<2>(study_cell(ours, row, p));
            const bool short_run = now.t_first * full.steps < 1.0;
            now.t_step = t_study;
            if (!std::isfinite(t_study) || short_run || round > 0) {
                set_thread_count(1);
                RunResult whole;
                const auto time_whole = [&] { whole = run(initial, *law, problem.domain, full); };
                const Least w =
                    short_run ? least_of_repeats(time_whole) : least_of_repeats(time_whole, 0.0, 1);
                now.t_step = w.cpu / std::max(1, whole.steps_done);
            }
            times[static_cast<std::size_t>(row * 5 + p)].lower(now);
            fmt::print(stderr, "round {}: {} row {} P {}: {:.2e} s/step\n", round + 1, spec.problem,
                       row + 1, p, now.t_step);
        }
    }
}

std::string cell_table(const TableSpec& spec, int rows,
                       const std::map<std::tuple<std::string, int, int>, PaperCell>& paper,
                       const StudyCells& ours, const std::vector<CellTimes>& times,
                       Totals& totals) {
    const Problem problem = make_problem(spec.problem);
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    std::string md = fmt::format(
        "### {} ({})\n\n| N/S/K/ε | P | E ours | E paper | T ours | T paper | paper / ours | "
        "T first steps | G per vertex | step | floor | step / floor | speed-up {} threads |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
        spec.title, spec.problem, cores);
    for (int row = 0; row < rows; ++row) {
        for (int p = 0; p < 5; ++p) {
            const RunOptions full = study_cell_options(problem, row, p, RunOptions{});
            const CellTimes& c = times[static_cast<std::size_t>(row * 5 + p)];
            const PaperCell ref = paper.count({spec.table, full.steps, p})
                                      ? paper.at({spec.table, full.steps, p})
                                      : PaperCell{NAN, NAN};
            const auto [e, evals, t_study] = study_cell(ours, row, p);
            const double speedup = c.wall_one / c.wall_all;
            const double ratio = ref.t_step / c.t_step;
            const double over_floor = c.floor.step_s / c.floor.floor_s();
            totals.ratios.push_back(ratio);
            if (std::isfinite(over_floor)) totals.floors.push_back(over_floor);
            const double floor_ratio = ref.t_step / c.floor.floor_s();
            if (std::isfinite(floor_ratio)) totals.paper_over_floor.push_back(floor_ratio);
            totals.speedups.push_back(speedup);
            totals.speedup_of[{spec.problem, row, p}] = speedup;
            if (std::isfinite(evals)) totals.evals.push_back(evals);
            md += fmt::format(
                "| {}/{}/{}/{:.0e} | {} | {} | {} | {:.2e} | {} | {:.0f}× | {:.2e} | {:.2f} | "
                "{:.2e} | {:.2e} | {:.2f} | {:.2f} |\n",
                full.steps, full.step.embedded.smoothing, full.step.contour.depth,
                full.step.contour.resolved_eps(), p, sci(e), sci(ref.e_inf), c.t_step,
                sci(ref.t_step), ratio, c.t_first, evals, c.floor.step_s, c.floor.floor_s(),
                over_floor, speedup);
        }
    }
    return md + "\n";
}

double median(std::vector<double> v) {
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

/// One step of a circle of radius 1 under rotation about its centre, the contour depth chosen
/// so that the result has about `target` segments.
std::string scaling_table(std::size_t max_segments, int rounds) {
    std::string md =
        "| segments | K | P | s per step, 1 thread | µs per segment | s / (N log₂ N) ×10⁹ | "
        "speed-up 2 threads | same curve on 2 threads |\n|---|---|---|---|---|---|---|---|\n";
    const auto law = make_velocity("rotation");
    const Box domain = Box::centered_square(2.0);
    struct Row {
        int depth = 0;
        std::size_t segments = 0;
        double t1 = 0.0, wall1 = 0.0, wall2 = 0.0;
        bool same = true;
    };
    std::vector<Row> table;
    constexpr int passes = 2;
    // Every row once per round, each time the least over the rounds (see time_cells).
    for (int round = 0; round < rounds; ++round) {
        std::size_t row = 0;
        for (int depth = 4; depth <= 16; depth += 2, ++row) {
            // A polygon about as fine as the contour it will give: four segments per finest cell.
            const int n = std::max(32, static_cast<int>(4.0 * 2.0 * std::numbers::pi /
                                                        (4.0 * std::ldexp(1.0, -depth)) / 1.5));
            const Interface circle(std::vector<std::vector<Vec2>>{shapes::circle({}, 1.0, n)});
            StepOptions o;
            o.contour.depth = depth;
            o.contour.refine_passes = passes;
            o.contour.eps = std::ldexp(1.0, -2 * depth);
            const double k = 2.0 * std::numbers::pi / 64.0;
            set_thread_count(1);
            StepResult one, two;
            const Least on_one =
                least_of_repeats([&] { one = advance(circle, 0.0, k, *law, domain, o); });
            set_thread_count(2);
            const Least on_two =
                least_of_repeats([&] { two = advance(circle, 0.0, k, *law, domain, o); });
            const bool same = std::equal(one.curves.points().begin(), one.curves.points().end(),
                                         two.curves.points().begin(), two.curves.points().end(),
                                         [](Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; });
            if (row == table.size()) {
                table.push_back(
                    {depth, one.curves.size(), on_one.cpu, on_one.wall, on_two.wall, same});
            } else {
                Row& r = table[row];
                r.t1 = std::min(r.t1, on_one.cpu);
                r.wall1 = std::min(r.wall1, on_one.wall);
                r.wall2 = std::min(r.wall2, on_two.wall);
                r.same = r.same && same;
            }
            fmt::print(stderr, "scaling, round {}: {} segments, {:.3g} s\n", round + 1,
                       one.curves.size(), on_one.cpu);
            if (one.curves.size() > max_segments) break;
        }
    }
    for (const Row& r : table) {
        const double segments = static_cast<double>(r.segments);
        md += fmt::format("| {} | {} | {} | {:.3g} | {:.3g} | {:.3g} | {:.2f} | {} |\n", r.segments,
                          r.depth, passes, r.t1, 1e6 * r.t1 / segments,
                          1e9 * r.t1 / (segments * std::log2(segments)), r.wall1 / r.wall2,
                          r.same ? "identical" : "DIFFERENT");
    }
    return md + "\n";
}

/// Largest distance from the vertices of curves to the exact curve, by the problem's exact
/// signed distance.
double vertex_error(const Problem& p, const Interface& curves, double t) {
    const std::vector<Vec2> v(curves.points().begin(), curves.points().end());
    const auto d = p.exact(v, t);
    double worst = 0.0;
    for (double x : *d) worst = std::max(worst, std::abs(x));
    return worst;
}

struct PeerRun {
    std::string name{};
    std::string settings{};
    std::map<std::string, double> params{};
    int steps = 0, depth = 0, refine = 0;
    double eps = 0.0;
    std::optional<int> mesh{};
    Extension extension = Extension::nearest_point;
    std::optional<double> t_end{};       ///< the problem's own when not given
    std::optional<double> half_width{};  ///< the domain [−b, b]², the problem's own when not given
    std::optional<GeometryModule> module{};  ///< the problem's own when not given
    bool arcs = false;                       ///< StepOptions::arcs
};

/// Runs a peer comparison on one thread: the problem's setting with r's method options, three
/// times. Returns the problem (with its domain), the initial curves and the result, with the
/// least wall time of the three runs.
std::tuple<Problem, Interface, RunResult> run_peer(const PeerRun& r) {
    Problem p = make_problem(r.name, r.params);
    if (r.half_width) p.domain = Box::centered_square(*r.half_width);
    const auto law = make_velocity(p.velocity, p.velocity_params, r.module ? r.module : p.module);
    Interface initial = prepare_interface(p.initial, p.domain).curves;
    RunOptions o;
    o.step.arcs = r.arcs;
    o.t_start = p.t_start;
    o.t_end = r.t_end.value_or(p.t_end);
    o.steps = r.steps;
    o.step.contour.depth = r.depth;
    o.step.contour.refine_passes = r.refine;
    o.step.contour.eps = r.eps;
    o.step.extension = r.extension;
    o.step.embedded.mesh = r.mesh.value_or(default_mesh_size(r.depth));
    o.step.embedded.smoothing = p.smoothing;
    set_thread_count(1);
    // The least wall time of three runs (the same result each time), as for the cells.
    RunResult result = run(initial, *law, p.domain, o);
    for (int again = 1; again < 3; ++again)
        result.wall_s = std::min(result.wall_s, run(initial, *law, p.domain, o).wall_s);
    return {std::move(p), std::move(initial), std::move(result)};
}

/// One program's setting beside the others: its error and seconds.
struct PeerPoint {
    std::string program;
    double error = 0.0, seconds = 0.0;
};

/// log10 error against log10 seconds, a colour per program, and the goal's corner: as accurate as
/// the best peer and 7× faster (its lower-left quadrant). The settings of a program named in
/// `refinements` are one setting refined, joined by a line; others are dots. Written to path.
void plot_peers(const std::filesystem::path& path, const std::string& title,
                const std::vector<PeerPoint>& points, PeerPoint best,
                const std::set<std::string>& refinements) {
    std::map<std::string, std::vector<Vec2>> lines;
    Box b = Box::empty();
    for (const PeerPoint& q : points) {
        if (!(q.error > 0) || !(q.seconds > 0)) continue;
        const Vec2 v{std::log10(q.seconds), std::log10(q.error)};
        lines[q.program].push_back(v);
        b = unite(b, {v, v});
    }
    const Vec2 goal{std::log10(best.seconds / 7.0), std::log10(best.error)};
    b = unite(b, {goal, goal});
    const double half = 0.55 * std::max({b.width(), b.height(), 1.0});
    Figure fig(Box::square(b.center(), half), title);
    fig.set_axis_names("log10 seconds", "log10 error");
    const Vec2 corner[] = {{goal.x, b.center().y - half}, goal, {b.center().x - half, goal.y}};
    fig.add_polyline(corner, "goal: as accurate as the best peer, 7× faster",
                     Color{0.6, 0.6, 0.6, 1}, 1.0);
    std::size_t i = 0;
    for (auto& [program, line] : lines) {
        std::sort(line.begin(), line.end(), [](Vec2 a, Vec2 c) { return a.x < c.x; });
        // A single point draws no line but still names the colour in the legend.
        fig.add_polyline(refinements.count(program) ? std::span<const Vec2>(line)
                                                    : std::span<const Vec2>(line).first(1),
                         program, palette_color(i));
        fig.add_points(line, palette_color(i), 3.0);
        ++i;
    }
    fig.save(path);
}

std::string peers_section(const std::filesystem::path& figures) {
    std::string md;
    std::filesystem::create_directories(figures);
    // Zalesak's disk: one turn in t = 1.
    md +=
        "### Zalesak's slotted disk, one turn ([0, 1]², one core, wall time of the time loop)\n\n"
        "With the law sampled directly (`--extension direct`) each step traces the characteristics "
        "back by the fourth-order Runge–Kutta rule, in as many substeps as bring the feet within "
        "ε/10, and contours once, so a few steps per turn suffice; the default nearest-point "
        "extension is second order in time and contours twice per step. Refinement finds the "
        "slot's corners where the lines of their sides meet (docs/algorithms/contour.md). The area "
        "change is relative, (A(1) − A(0)) / A(0), for every program.\n\n"
        "| program | setting | largest vertex distance to the exact shape | area change | "
        "seconds |\n|---|---|---|---|---|\n"
        "| FronTier (front tracking) | 256² | 1.28e-3 | −3.95e-4 | 7.7 |\n"
        "| LSMLIB (WENO5 + TVD-RK3 level set) | 256² | 4.4e-3 | −1.4e-3 | 16.3 |\n";
    std::vector<PeerPoint> zalesak_points = {{"FronTier", 1.28e-3, 7.7}, {"LSMLIB", 4.4e-3, 16.3}};
    auto zalesak_run = [](std::string settings, int steps, int depth, int refine, double eps,
                          Extension extension) {
        return PeerRun{.name = "zalesak",
                       .settings = std::move(settings),
                       .steps = steps,
                       .depth = depth,
                       .refine = refine,
                       .eps = eps,
                       .extension = extension,
                       .arcs = extension == Extension::direct};
    };
    const std::vector<PeerRun> zalesak = {
        zalesak_run("N/K/P/ε = 100/7/2/1e-6, nearest-point extension (default)", 100, 7, 2, 1e-6,
                    Extension::nearest_point),
        zalesak_run("4/7/2/1e-6, direct velocity, arcs", 4, 7, 2, 1e-6, Extension::direct),
        zalesak_run("16/7/2/1e-6, direct velocity, arcs", 16, 7, 2, 1e-6, Extension::direct),
        zalesak_run("8/8/2/1e-7, direct velocity, arcs", 8, 8, 2, 1e-7, Extension::direct),
        zalesak_run("8/9/2/1e-8, direct velocity, arcs", 8, 9, 2, 1e-8, Extension::direct),
    };
    Interface exact_disk;
    std::vector<std::pair<std::string, Interface>> shapes;
    for (const PeerRun& r : zalesak) {
        const auto [p, initial, result] = run_peer(r);
        const double error = vertex_error(p, result.curves, result.t);
        md += fmt::format("| slc | {} | {:.3g} | {:+.2g} | {:.3g} |\n", r.settings, error,
                          (area(result.curves) - area(initial)) / area(initial), result.wall_s);
        zalesak_points.push_back(
            {r.extension == Extension::direct ? "slc, direct velocity" : "slc, nearest-point",
             error, result.wall_s});
        if (r.extension == Extension::direct)
            shapes.emplace_back(fmt::format("slc {}", r.settings.substr(0, r.settings.find(','))),
                                result.curves);
        exact_disk = initial;
    }
    plot_peers(figures / "performance_zalesak.png", "Zalesak's disk, one turn: error and seconds",
               zalesak_points, {"FronTier", 1.28e-3, 7.7}, {"LSMLIB", "slc, direct velocity"});
    // The slot's mouth after one turn, where the convex corners are: the exact shape (the
    // initial one) and the direct runs.
    Figure slot(Box::square({0.5, 0.62}, 0.04), "Zalesak's disk after one turn: the slot's mouth");
    slot.add_curves(exact_disk, "exact", Color{0.4, 0.4, 0.4, 1}, 3.0);
    for (std::size_t i = 0; i < shapes.size(); ++i)
        slot.add_curves(shapes[i].second, shapes[i].first, palette_color(i), 1.2);
    slot.save(figures / "performance_zalesak_slot.png");
    md +=
        "\n![error against seconds](figures/performance_zalesak.png)\n"
        "![the slot's mouth after one turn](figures/performance_zalesak_slot.png)\n";

    // Curve shortening of a circle R(0) = 0.5 to t = 0.1: R(t)² = R(0)² − 2t. With the
    // embedded module the problem's S = 1 keeps k/h² ≤ 1.6 stable (docs/user-guide.md §5); the
    // arclength module averages over √k, stable at any K.
    md +=
        "\n### Curve shortening of a circle, R(0) = 0.5 to t = 0.1 (one core)\n\n"
        "The paper's embedded module (S = 1) reads the curvature from a Cartesian mesh, with a "
        "bias of about 0.1% that a finer mesh removes only slowly, and the chords of the polygon "
        "lose a little more with each step; `--geometry arclength --arcs` takes the curvature of "
        "the circles through neighbouring vertices, averaged along the curve over √k, and reads "
        "the polygon as arcs through its vertices (docs/algorithms/geometry.md, evolve.md). The "
        "error is the largest distance of a vertex from the exact circle.\n\n"
        "| program | setting | radius error | seconds |\n|---|---|---|---|\n"
        "| LSMLIB | 128² | 1.1e-4 | 0.48 |\n| LSMLIB | 256² | 2.9e-5 | 7.7 |\n";
    std::vector<PeerPoint> shortening_points = {{"LSMLIB", 1.1e-4, 0.48}, {"LSMLIB", 2.9e-5, 7.7}};
    auto shortening_run = [](std::string settings, int steps, int depth, double eps,
                             std::optional<int> mesh, std::optional<double> half_width,
                             bool arclength = false) {
        return PeerRun{
            .name = "circle-curvature",
            .settings = std::move(settings),
            .params = {{"R0", 0.5}},
            .steps = steps,
            .depth = depth,
            .refine = 2,
            .eps = eps,
            .mesh = mesh,
            .t_end = 0.1,
            .half_width = half_width,
            .module = arclength ? std::optional(GeometryModule::arclength) : std::nullopt,
            .arcs = arclength};
    };
    const std::vector<PeerRun> shortening = {
        shortening_run("N/K/P/ε/M = 20/8/2/1e-8/128 in [−4, 4]², embedded", 20, 8, 1e-8, 128, {}),
        shortening_run("10/6/2/1e-7/32 in [−1, 1]², embedded", 10, 6, 1e-7, 32, 1.0),
        shortening_run("10/4/2/1e-6 in [−1, 1]², arclength, arcs", 10, 4, 1e-6, {}, 1.0, true),
        shortening_run("10/5/2/1e-7 in [−1, 1]², arclength, arcs", 10, 5, 1e-7, {}, 1.0, true),
        shortening_run("20/5/2/1e-8 in [−1, 1]², arclength, arcs", 20, 5, 1e-8, {}, 1.0, true),
        shortening_run("40/6/2/1e-8 in [−1, 1]², arclength, arcs", 40, 6, 1e-8, {}, 1.0, true),
    };
    for (const PeerRun& r : shortening) {
        const auto [p, initial, result] = run_peer(r);
        const double exact = std::sqrt(0.25 - 2.0 * 0.1);
        double worst = std::numeric_limits<double>::quiet_NaN();
        if (!result.curves.empty()) {
            worst = 0.0;
            for (Vec2 v : result.curves.points())
                worst = std::max(worst, std::abs(norm(v) - exact));
        }
        md += fmt::format("| slc | {} | {:.3g} | {:.3g} |\n", r.settings, worst, result.wall_s);
        shortening_points.push_back(
            {r.arcs ? "slc, arclength and arcs" : "slc, embedded", worst, result.wall_s});
    }
    plot_peers(figures / "performance_curve_shortening.png",
               "Curve shortening of a circle: error and seconds", shortening_points,
               {"LSMLIB", 1.1e-4, 0.48}, {"LSMLIB", "slc, arclength and arcs"});
    md += "\n![error against seconds](figures/performance_curve_shortening.png)\n";
    return md + "\n";
}

/// The section on moving surfaces that bench/surface_performance_bench.cpp wrote into the file
/// at `path`, markers included, so that writing the rest of the file keeps it; empty if none.
std::string surfaces_section(const std::string& path) {
    if (!std::filesystem::exists(path)) return "";
    const std::string text = read_text_file(path);
    const std::string end = std::string(bench::surfaces_end) + "\n";
    const auto b = text.find(bench::surfaces_begin), e = text.find(end);
    if (b == std::string::npos || e == std::string::npos || e < b) return "";
    return text.substr(b, e + end.size() - b) + "\n";
}

}  // namespace

int main(int argc, char** argv) {
    slc::keep_freed_memory();  // as the slc tool does: the timings are the tool's
    using slc::bench::take_flag;
    const std::string out = take_flag(argc, argv, "--out", "docs/performance.md");
    const std::string study_dir = take_flag(argc, argv, "--study", "out/study");
    const std::string reference =
        take_flag(argc, argv, "--reference", "data/paper_convergence_tables.csv");
    const int rows = std::stoi(take_flag(argc, argv, "--rows", "5"));
    const int prefix = std::stoi(take_flag(argc, argv, "--prefix", "16"));
    const int rounds = std::stoi(take_flag(argc, argv, "--rounds", "2"));
    if (rounds < 1) {
        fmt::print(stderr, "performance_bench: --rounds must be at least 1, got {}\n", rounds);
        return 2;
    }
    const auto max_segments =
        static_cast<std::size_t>(std::stod(take_flag(argc, argv, "--max-segments", "1e6")));
    const auto paper = read_reference(reference);

    std::string md = fmt::format(
        "# Performance\n\nWritten by `scripts/bench` (bench/performance_bench.cpp); do not edit by "
        "hand. Machine: {} hardware threads; the paper's times are from a 450 MHz UltraSPARC II "
        "(2000). This program, like `slc`, keeps the memory a step frees for the next step "
        "(`slc::keep_freed_memory()`).\n\n",
        std::thread::hardware_concurrency());
    md +=
        "## Every cell of Tables 5–7\n\n"
        "*E ours* and *G per vertex* are the full runs of the studies (`slc study`, the same on "
        "any "
        "number of threads). *T ours* is CPU seconds per step of the whole run on one thread, "
        "as the paper's T: where the run takes under a second, the least of at least three runs "
        "repeated for half a second (a single run of a few milliseconds would also carry the "
        "process's first page faults); else the study's own timing of its one run (`slc study "
        "--threads 1`), or a run here in a later round where that took less. *T first "
        "steps* is CPU seconds per step on one thread (that thread's CPU clock) over the first " +
        std::to_string(prefix) +
        " steps of the cell (same k), the least of at least three runs, repeated for half a "
        "second (at most fifty): the whole run costs more where the curves grow, and less where "
        "the first step, from the problem's finer initial polygon, weighs less over more steps. "
        "*step* and *floor* are one step, one thread, from the "
        "interface reached: the floor is the work no step can avoid — building the two distance "
        "trees, the vertex velocities of both curves, and three G evaluations per output vertex "
        "for each of the two contours, each the least of calls repeated for a fifth of a second. "
        "*speed-up* is wall time on one thread over wall time on "
        "all, for the same steps (least wall times of the repeated runs). Every cell is timed in " +
        std::to_string(rounds) +
        " rounds, minutes apart, and each time above is the least over the rounds: spells of "
        "seconds in which the same code runs slower (on this machine up to 1.45×) then slow at "
        "most one round of a cell.\n\n";
    Totals totals;
    const TableSpec tables[] = {
        {"table5_rotation", "propeller-rotation", "Table 5, rotating propeller"},
        {"table6_merging", "merging-circles", "Table 6, merging circles"},
        {"table7_curvature", "circle-curvature", "Table 7, circle under curvature"},
    };
    // Rounds: see the comment at the top of this file.
    StudyCells studies[std::size(tables)];
    for (std::size_t t = 0; t < std::size(tables); ++t)
        studies[t] = read_study(fmt::format("{}/{}/table.json", study_dir, tables[t].problem));
    std::vector<CellTimes> times[std::size(tables)];
    for (int round = 0; round < rounds; ++round)
        for (std::size_t t = 0; t < std::size(tables); ++t)
            time_cells(tables[t], rows, prefix, studies[t], round, times[t]);
    std::string cells;
    for (std::size_t t = 0; t < std::size(tables); ++t)
        cells += cell_table(tables[t], rows, paper, studies[t], times[t], totals);
    const auto at_least = [&](double goal) {
        return std::count_if(totals.ratios.begin(), totals.ratios.end(),
                             [&](double r) { return r >= goal; });
    };
    // NaN for an empty list (no cell gave a value).
    auto least = [](const std::vector<double>& v) {
        return v.empty() ? NAN : *std::min_element(v.begin(), v.end());
    };
    auto most = [](const std::vector<double>& v) {
        return v.empty() ? NAN : *std::max_element(v.begin(), v.end());
    };
    md += fmt::format(
        "Summary over {} cells: the paper's time over ours per step ranges from {:.0f}× to "
        "{:.0f}× (median {:.0f}×); {} cells reach 1000×. A step takes {:.2f}× to {:.2f}× its "
        "floor (median {:.2f}×; goal ≤ 3×). G evaluations per output vertex: at most {:.2f} "
        "(goal ≤ 8). Speed-up from 1 to {} threads: median {:.2f}×, least {:.2f}× (goal ≥ "
        "1.8×).\n\n",
        totals.ratios.size(), least(totals.ratios), most(totals.ratios), median(totals.ratios),
        at_least(1000.0), least(totals.floors), most(totals.floors), median(totals.floors),
        most(totals.evals), std::thread::hardware_concurrency(), median(totals.speedups),
        least(totals.speedups));
    const auto floor_short =
        std::count_if(totals.paper_over_floor.begin(), totals.paper_over_floor.end(),
                      [](double r) { return r < 1000.0; });
    md += fmt::format(
        "A step that cost only its floor would be {:.0f}× to {:.0f}× faster than the paper's "
        "(median {:.0f}×), short of 1000× in {} of {} cells: there, 1000× needs cheaper "
        "closest-point queries, velocities and trees, not only less work beside them.\n\n",
        least(totals.paper_over_floor), most(totals.paper_over_floor),
        median(totals.paper_over_floor), floor_short, totals.paper_over_floor.size());
    md += cells;
    md +=
        "## Scaling with the number of segments\n\nOne step of a circle of radius 1 rotating about "
        "its centre in [−2, 2]², P = 2, ε = 4^−K, the polygon about as fine as the contour; "
        "each time the least of repeated calls (at least three, for half a second), and the "
        "least over the rounds, as for the cells. N log N growth shows as a flat last-but-two "
        "column.\n\n";
    md += scaling_table(max_segments, rounds);
    md +=
        "## Beside the programs users would pick instead\n\nThe peers' numbers are theirs, "
        "measured on this kind of machine; ours are measured here on one core, the least wall "
        "time of three runs of the same setting.\n\n";
    md += peers_section(std::filesystem::path(out).parent_path() / "figures");
    md += surfaces_section(out);
    md += R"(## Where the time goes

A profile of one step of Table 5's 320/0/6/4/1e−6 cell (4424 segments, one thread; `valgrind
--tool=callgrind` instruction counts, 4.2·10⁸ for the step) showed:

| part of the step | share |
|---|---|
| closest-point queries (all G evaluations and extensions) | 48% |
| of which: the segment hierarchy, for points far from Γ | 20% |
| building the two distance trees (lists and 2:1 balance) | 24% |
| G at the contouring tree's corners and centres (topology stage) | 15% |
| root finding on the linear contour's triangle edges | 14% |
| refinement's safeguards (segment grid, crossing checks) | 9% |

What it changed: the first profile of the same step spent 45% in the topology stage, where
points far from Γ met cell lists of thousands of segments, and 42% of a contour of a distance
function in crossing checks against a grid sized for the unrefined contour. Queries meeting a list
longer than 48 segments now descend a bounding-box hierarchy over runs of consecutive segments
(exact, the same answer as the scan); the safeguards' grid is rebuilt each refinement pass at twice
the mean segment length, and crossing checks reject disjoint bounding boxes before the exact test;
tree lists are written in place in cell order instead of one vector per cell; the leaf is found
from a grid two levels above the leaves over a compact child array. Each change left every result
bit-identical. What remains: the nearest-point extension is evaluated at points a whole step
(|k W|) from Γ(t), where an exact nearest segment needs lists of 2|kW| / (segment length) segments
— the step's main cost, and what keeps the finest cells from 1000×.

### Without refinement (P = 0)

The cells with P = 0 sat furthest above their floor (up to 7.7×). A profile of Table 5's
640/0/7/0 (`perf record`, one thread) found 78% of the step in the topology stage: the contouring
tree's sample points far from Γ cost 500–1000 ns per evaluation of G (each of its two or four
closest-point queries meets long lists there) against 160–220 ns near Γ, and 4602 of them per
contour against 2261 evaluations for root finding. The step's G changes no faster than the
distance moved plus twice the foot's largest move d = k max|W|, and differs from F(x; Γ(t)) by at
most d; so a tree point whose parent cell's values, or one distance query, already place |G|
above the split threshold needs no evaluation — the bound, with its certain sign, stands in
(docs/algorithms/contour.md). The trees and contours are bit-identical; the tree's evaluations
per contour fall from 4565 to 2464 there (from 3501 to 1144 at Table 6's 640/0/7/0), the G
evaluations per output vertex of every cell are now at most the goal's 8, and the P = 0 steps are
1.4–1.7× faster. The same profile now: evaluations of G 36% of the step (tree 20%, root finding
15%), the lower bound's queries 8%, the two distance trees 16%, and the contouring tree's own
bookkeeping (its table of sample points, 2:1 balance checks, triangulation) about 28%. Refinement
also gives up a bracket across a jump of G at once (its split would be refused anyway) instead of
bisecting it to rounding size: at Table 5's 40/0/3/4 the evaluations per output vertex fell from
8.86 to 6.82.

### The query kernel and the balance pass

With 18 to 32 segments scanned per query near Γ (Table 6's 640/0/7/4: 32 on average, 1.0 climbs
per query), the closest point on a segment is the innermost loop, and its clamp waited for a
division whose result most segments do not need: the parameter's sign and its size against the
squared length now decide the endpoints first (the same answer to the last bit, tested against
the definition). A query near Γ became 5–10% faster. The distance trees' 2:1 balance pass asked
every leaf for its four neighbours, again for each leaf it split; it now asks only the cells with
children for their four same-level neighbours — the tree is balanced exactly when none is
missing — a third as many cells: building the tree of Table 5's 320/0/6/4 interface (3806
segments, L = 8) went from 3.42 to 1.86 ms. Both leave every result bit-identical; whole steps
became 1.05–1.07× faster.

### Tables of points, and what did not pay

The contouring tree looks up each of its sample points, and the triangulation each of its
vertices, in a hash table; std::unordered_map kept a node per entry, a cache miss per lookup. Both
now use one flat table (`KeyMap`: open addressing, each key beside its value), and refinement's
chain keeps its segments' lengths instead of taking each several times a pass (a `std::hypot`
each). Results are bit-identical; one thread, least of four runs from the interface after 16
steps: Table 6's 160/0/5/2 step 5.15 → 4.61 ms (0.90×), Table 5's 40/0/3/0 0.287 → 0.269 ms
(0.94×), 640/0/7/0 10.3 → 10.1 ms (0.98×), 320/0/6/4 39.4 → 38.7 ms (0.98×), Table 7's
320/3/7/4 91.5 → 88.8 ms (0.97×). The cell box and lattice point that every query computes are
inline now (they were calls into another library): 1.5–4% more, bit-identical. On this machine
the same measurement varies by up to ±15% between runs minutes apart, so gains of a few percent
show in interleaved runs, not in one bench against the last. Measured and not kept: precomputed
vertex pseudo-normals for the sign (no gain beyond the noise, ±4%); leaf lists ordered by their
segments' box distance, with the scan stopped once that exceeds the best distance (bit-identical, but
building the order cost more than it saved: 640/0/7/0 10.2 → 11.3 ms); a closest-point
kernel without branches (1% slower); dynamic scheduling of the parallel loops (5–9% slower on
two threads); and `sqrt(x² + y²)` for `std::hypot` (1–6% faster, but not bit-identical, and the
merging circles' cusp bubbles turn last-bit changes into E∞ changes of −9% to +16% per cell of
Table 6's third row). A profile of Table 5's 320/0/6/4 now: closest-point queries 34%, the
segment hierarchy 19% (points far from Γ, two thirds of them the contouring tree's samples and
their lower bounds), building the distance trees 10%, refinement's safeguards 7%.

### Bounds on G as intervals

The contouring tree's bound was a lower bound of |G| with its sign, used only to settle a point at
its cell's split threshold; every other point was evaluated. The bounds are now intervals holding
G: a parent's sample y gives |G(y)| ± (|x − y| + δ), the step's caller F(x) ± d(x). A point whose
sign either gives keeps a stand-in with both bounds; a cell splits without any value where a
sample's upper bound is below its threshold; and a test evaluates only the stand-ins it needs,
after offering those the parents made to the caller's bounds (docs/algorithms/contour.md). The
predictor's d(x) is k|W(x)|, W read from the same query, instead of k max|W|, and |G̃(x)| is at
most the foot's distance to the point of Γ(t) nearest x. Contours bit-identical; at Table 5's
640/0/7/0 the tree's evaluations per contour (predictor / corrector, from the interface after 16
steps) fell from 4003 / 4003 to 1359 / 1967, with 4600 / 4588 bound evaluations instead of
2973 / 2966; at Table 6's 640/0/7/0 from 1176 to 708. Whole steps, one thread, least of four
interleaved runs: Table 5's 40/0/3/0 0.87×, 640/0/7/0 0.91×, 320/0/6/4 0.97×, 640/0/7/4 0.91×,
Table 6's 160/0/5/0 0.87×, 160/0/5/2 0.92×, 640/0/7/4 0.96×, Table 7's 320/3/7/4 0.95×. Measured
and not kept: a table of Γ(t)'s closest points at the tree's sample points, shared by the
bounds, the predictor and the corrector (bit-identical; 20–30% of all queries repeat at P = 0,
3–6% at P ≥ 2, but the lookups cost about what they saved: 0.97–1.03×); the segment hierarchy for
lists longer than 24 or 96 segments instead of 48 (1.16× slower; 0.98–1.03×); a stack that keeps
each node's box distance in the hierarchy (noise); a bounding-box test before each segment of a
list (1.11–1.22× slower: the kernel is cheaper than the test's mispredicted branches); and
compiling for x86-64-v3 without FMA contraction (0.96×, but the binaries would no longer run
on every x86-64). A profile of whole runs of Table 5's 40/0/3/1e−3 cell with P = 1,
the furthest from 1000×: closest-point queries 61% (each of the ~18 segments scanned per query is
the innermost loop), root finding 38% of the step (3.5 to 6.3 evaluations per root, to the
paper's η = 10⁻¹⁰ on the edges of a tree of depth 3), the contouring tree 30%, the
distance trees 8%.

Within a run, a step costs more than the same step repeated from one interface, as the *step*
column times it: at Table 5's 40/0/3/1e−3 cell with P = 1, step 16 repeated takes 0.38 ms, and
0.40–0.47 ms alternated with step 17 (which takes 0.52 ms); in sequence, the least of 100 runs,
the steps from the second on take 0.46–0.59 ms (the first, from the 1024-vertex initial polygon,
1.34 ms). This is part of why *T ours* exceeds *step* in the smallest cells.

### The contouring tree's samples, and memory between steps

The contouring tree looked up a sample point in its hash table at every use (split tests, donors,
leaf centres); its triangulation kept a second table of vertices and asked the tree for every
leaf's four neighbours; and every vertex was then looked up again for its value. Now the samples
live in one array and every cell keeps the ids of its samples, which the tests, the donors and the
triangulation read: a leaf's edge midpoint is a sample exactly where the neighbour across is
finer, so it takes one lookup and no search for neighbours (tested against `triangulate()` on
graded trees). The distance tree filters the children's lists into an uninitialized scratch
buffer instead of a zero-filled vector resized at every level, which halves the page faults of a
Table 7 step. And `slc`, like this bench, keeps the memory a step frees for the next step
(`keep_freed_memory()`), which glibc would otherwise hand back to the system and fault in again
every step: 0.94–0.975× per step in four cells on its own. Results are bit-identical (the same
final vertices in four whole runs). One thread, least of six interleaved runs from the interface
after 16 steps, against the version before: Table 5's 640/0/7/1e−7 with P = 0 0.86×, Table 6's
0.80×, Table 5's 40/0/3/1e−3 with P = 1 0.92×, 320/0/6/1e−6 with P = 4 0.96×, Table 6's
160/0/5/1e−5 with P = 2 0.97×; Table 7's 160/2/6/1e−6 with P = 4 within the noise (0.94–1.04×
in repeated comparisons).

### On two threads

On two threads this step took 1/1.34 of its one-thread time. What ran on one thread only:
building the distance trees, the 2:1 balance checks, the safeguards' segment grid (a vector per
cell, allocated anew each refinement pass), batches of fewer than 256 points, and page faults on
freshly allocated arrays. The distance trees now grow a level at a time on all threads (the same
cells and lists for any thread count, tested), the contouring tree's balance check runs over
its cells in parallel, batches of G and of closest-point queries go parallel from 32 points, bracket reaches
are found in parallel, and the segment grid keeps its entries in one array. A profile on two
threads (`perf record -e cpu-clock`, samples counted per thread) then found the second thread
waiting at the end of parallel loops for 47% of the step. What runs on one thread: refinement's
acceptance loop (each candidate must see the vertices its predecessors added, so its crossing
tests run in order), the contouring tree's splits, its table of sample points and its
triangulation, and page faults (10% of the main thread's samples).
)";
    const auto speedup = [&](const char* problem, int row, int p) {
        const auto it = totals.speedup_of.find({problem, row, p});
        return it == totals.speedup_of.end() ? NAN : it->second;
    };
    md += fmt::format(
        "\nMeasured now (the tables above): this step's speed-up on {} threads is {:.2f}×; Table "
        "6's 160/0/5/1e−5 cell with P = 2 has {:.2f}× over its first steps, from the three "
        "small circles. An earlier timing of that cell's stages (before the interval bounds; "
        "200 steps from the interface after 16, the step 1121 → 825 ms, 1.36×) on one and two "
        "threads gave: the contouring tree "
        "(topology stage) 301 → 241 ms (1.25×), refinement 503 → 352 ms (1.43×), root finding "
        "113 → 69 ms (1.64×), the two distance trees 172 → 133 ms (1.30×). The contouring tree's "
        "own bookkeeping, outside its "
        "batches of G, is about a quarter of its one-thread time and runs on one thread; so do "
        "the acceptance loop (84 ms of the 503), the midpoint selection and the pruning.\n\n",
        std::thread::hardware_concurrency(), speedup("propeller-rotation", 3, 4),
        speedup("merging-circles", 2, 2));
    md += R"(Measured and not kept since:

- The contouring tree's bookkeeping on all threads: each new point's stand-in from its parent's
  samples, the leaf centres, the bounds' updates and the vertices' values worked out in parallel
  and entered in cell order, and the triangulation's neighbour searches in parallel (results
  bit-identical). The one-circle step of 43770 segments (K = 12) took 0.90× its two-thread time,
  but Table 5's 640/0/7/1e−7 cell with P = 0 took 1.15–1.19× its one-thread time (the staging
  arrays and their page faults), and up to 1.49× on two threads. Without the new points' and the
  centres' stand-ins, the rest gained nothing beyond the noise (0.93–1.05× on one thread,
  1.01–1.02× on two). A two-thread profile of the 43770-segment step shows why: the second
  thread waits for 30% of the step while the first runs a long tail of pieces of 1–3% each. The
  largest are the tree's table of sample points (about 6% of all samples), the triangulation
  (5%), refinement's crossing tests (3%), and page faults and copies (3%).
- Handing the bounds' closest-point queries to the batch of G after them. The tree evaluates G
  next at the points of that batch whose sign the bounds left open, in the same order, and G
  starts with the same query. Results bit-identical, but it met only about half of the tree's
  evaluations (about 900 per contour at Table 5's 640/0/7/1e−7 with P = 0): the stand-ins of
  crossed triangles are evaluated later, away from their bounds' batch. Time: 1.06–1.08× there,
  0.98× at Table 6's 640/0/7/1e−7, 0.96× at Table 5's 40/0/3/1e−3 with P = 1.
- The four children's lists of a distance-tree cell in one pass over their parent's list, without
  branches (each segment stored at every child's next place and kept where its box meets that
  child's triple). The same lists, but building a tree took 1.05–1.13× as long in four of five
  interfaces (0.96× in one): the stores and their pages cost more than the branches they replaced.

### Velocity queries without a sign, and the corrector's foot

The nearest-point extension needs only where the nearest point of Γ lies, so its queries now skip
the side test (`DistanceTree::nearest_point`), which at a vertex takes two normals: three of the
corrector's four queries and one of the predictor's two. Results bit-identical (the same final
vertices in four whole runs). One thread, least of four interleaved runs from the interface after
16 steps, against the version before: Table 5's 160/0/5/1e−5 with P = 0 0.95×, 320/0/6/1e−6 with
P = 4 0.97×, Table 6's 160/0/5/1e−5 with P = 2 0.94×, Table 7's 160/2/6/1e−6 with P = 4 0.97×;
Table 5's 40/0/3/1e−3 cell 0.96–1.01× (noise).

The corrector's first query is the costliest: it asks for Γ(t)'s nearest point to x, a whole step
k|W| from Γ(t), where lists are long. Eq. 5 needs it for the foot x − kW(x, t). Measured and not
kept, each as whole studies of Tables 5–7 on one thread beside the current code (run side by side,
so the times compare only pairwise):

- The foot from the predicted velocity, x − kW̃(x, t + k), which the corrector has from its query
  near Γ̃ (three queries instead of four, none far from its curve). Table 5: E∞ 0.53–1.00× and T
  0.73–1.03×; Table 7: E∞ within 0.5%, T 0.87–1.08×. But Table 6: E∞ up to 3.1× (320/0/6/1e−6
  with P = 4: 0.000462 → 0.00145), the largest errors at the cusps where the circles merge. Under
  motion along the normal the paper's foot lands exactly on Γ(t)'s nearest point to x (Huygens'
  construction), which the predicted curve's normals near its own cusp do not reproduce.
- The same foot followed by two fixed-point steps of the trapezoidal rule: Table 5's E∞ then
  falls to 0.27–1.00× and is below the paper's in all 25 cells (now in 16), but Table 6's E∞ rises
  up to 1.9×, and steps take up to 1.73× as long.
- One more fixed-point step after the paper's foot (five queries): Table 5's E∞ 0.27–1.00×
  (below the paper's in 24 cells), but Table 6's up to 1.42× and steps up to 1.48× as long.

### Four segments at a time, and the distance tree's list array

Measured and not kept: the scan of a cell list four segments at a time (the closest point's
branches made selects, in an AVX2 clone picked at load time and an SSE2 one for any x86-64; the
same distances to the last bit, and whole runs bit-identical). Each query waits for the division
that the scalar kernel skips wherever an end of the segment is nearest, and the lists near Γ are
short (14–29 segments scanned per query in the cells of Tables 5–7): one query, least of 30 runs,
took 64 ns against 46 ns on a 40-segment curve in a tree of depth 3, and 102 ns against 148 ns
for points 0.3 from a 200-segment curve (long lists). Whole runs, least of three interleaved, new
over old: 0.97–1.04×; with the vector scan only for lists of 24 segments or more, 0.98–1.00×;
only in the segment hierarchy's runs of eight, the one-circle step of 43770 segments 0.98–1.00×.

Kept: the one array of all cell lists grows as `std::vector` would, but by `realloc` and without
zeroing its new entries, so an array large enough to be mapped on its own is moved, not copied,
and its pages are first touched by the threads that pack the lists. Trees and lists are
bit-identical (the same final vertices in eight whole runs, on one and two threads). Building the
tree of 240000 segments at depth 15 (127 MB of lists), least of three builds: 0.363 → 0.299 s on
one thread, 0.266 → 0.179 s on two (speed-up 1.36× → 1.67×); a tree of 43770 segments (20 MB)
builds in the same time as before. In the one-circle step of 240103 segments the two trees take
13% of the time on one thread, and the step on two threads went from 2.13–2.26 s to 2.02–2.15 s
(three interleaved runs each). A profile of that step on two threads: the segment hierarchy takes
37% of it (the feet of a rotating circle lie about 0.005 from Γ(t), where lists hold hundreds of
segments 2.6·10⁻⁵ long), and the second thread waits for about a fifth of the step while the first
runs the contouring tree's table of samples (3%), its topology (2.5%), refinement's crossing tests
(1.5%) and its centres (1.5%).

### The contouring tree's table of points, and its stand-ins on all threads

A two-thread profile of the one-circle step of 43770 segments (`perf record -e cpu-clock`,
samples counted per thread) found the second thread waiting for 30% of its samples. What the
first ran alone was led by the contouring tree: entering each new cell's five points in its table
of sample points (half of that time waiting for the table's memory), working out the new
points' stand-ins, the centres of the finest leaves, and looking up the midpoints of every leaf's
edges while triangulating. Now a new cell's corners are its parent's corners and centre, read
from the parent's samples, or the midpoints of its parent's edges, which alone go through the
table; a centre belongs to its cell only and is never entered; a leaf at the depth limit has no
finer neighbour, so its edges need no lookup; and the stand-ins of the new points and the leaf
centres are worked out on all threads, each point's from the parent of the first cell (in cell
order) that meets it. Refinement checks every candidate's triangle (may the new vertex leave its
segment's triangle?) on all threads before the acceptance loop, which needs only the angle and
crossing checks in order. Every result is bit-identical (the same final vertices in eight whole
runs, on one and two threads), and the second thread now waits for 23% of its samples.

Wall time per step, least of three interleaved runs (one run each at 240103 segments), before →
after:

| segments | 1 thread | 2 threads | speed-up |
|---|---|---|---|
| 1324 | 0.0219 → 0.0218 s | 0.0139 → 0.0136 s | 1.58 → 1.60 |
| 5253 | 0.0949 → 0.0942 s | 0.0549 → 0.0495 s | 1.73 → 1.90 |
| 43770 | 0.751 → 0.705 s | 0.427 → 0.373 s | 1.76 → 1.89 |
| 240103 | 3.91 → 3.82 s | 2.76 → 2.33 s | 1.41 → 1.64 |

The scaling table above comes from one run of this bench, and its speed-ups move by up to ±0.1
from run to run on this machine (43770 segments: 1.70 in the run before this change, 1.64 in the
run after it); so do the cells' speed-ups in Tables 5–7 (their median went from 1.42 to 1.37,
single cells by up to ±0.25 both ways). Interleaved runs compare two versions under the same load.

The cells of Tables 5–7 have small trees, whose tables stay in cache: one thread, least of four
interleaved whole runs, 0.98–1.01× (Table 5's 40/0/3/1e−3 with P = 0 and 1, 640/0/7/1e−7 with
P = 0, 320/0/6/1e−6 with P = 4; Table 6's 160/0/5/1e−5 with P = 2; Table 7's 320/3/7/1e−7 with
P = 4), and on two threads 0.98–1.00× of the wall time in five of those cells (Table 6's
640/0/7/1e−7 with P = 4, one run: 0.86×). Measured and not kept: root finding's
bookkeeping between its batches (the next iterate and the update of each bracket) on all
threads, 1.01–1.02× at 1324 to 43770 segments.

### The embedded module's ENO stencils

Table 7's cells take the vertex normals and curvature of both curves of a step from the embedded
module (exact F on a local mesh, ENO differences, ENO interpolation back to the vertices), and a
profile of its smallest cell, 20/1/3/1e−3 with P = 0, found the module's ENO work and local mesh
in a third of the step, most of it in the interpolation. Each row interpolation tabulated the undivided differences of its
eight-point window level by level, and the compiler's vector loads of each level waited for the
scalar stores of the level before (a load that spans two stores cannot be forwarded from them);
the Lagrange sum did the same with its prefix products. Short windows are now tabulated column by
column, the prefix product runs along with the sum, the three fields (two normal components and
the curvature) look up their rows once, and a lattice cell's row stencils, which depend on the
cell and the data but not on where in the cell the vertex lies, serve every vertex in that cell
(about two per cell at Table 7's first row, more than ten at its last). Building the local mesh, a
segment's run of lattice points in a row extends the run the previous segment left there instead
of adding one more to sort. Every result is bit-identical (the same final vertices in eight whole
runs, on one and two threads; `SeveralFieldsAndTheCellCacheGiveTheSingleFieldValues`).

The module on one circle, one thread, least of five interleaved runs, before → after:

| vertices | M | S | whole module | interpolation to the vertices |
|---|---|---|---|---|
| 48 | 16 | 1 | 114 → 88 µs | 49 → 27 µs |
| 330 | 64 | 1 | 589 → 349 µs | 315 → 109 µs |
| 4300 | 256 | 3 | 8.06 → 4.42 ms | 3.99 → 1.01 ms |

Whole runs of Table 7, one thread, least of four interleaved: 0.78× at 20/1/3/1e−3 with P = 0,
0.81× at 40/1/4/1e−4 with P = 4, 0.83× at 80/1/5/1e−5 with P = 2, 0.80× at 160/2/6/1e−6 with
P = 4, 0.78× at 320/3/7/1e−7 with P = 4. Tables 5 and 6 do not use the module. Most of what
remains of it is the exact distances at the mesh points, up to R = E + S lattice steps from Γ,
where the distance tree's lists are long.

Measured and not kept, for the closest-point queries that every step spends most of its time in:

- Starting each lattice point's query from the nearest segment of the point before it in its row
  (the same answers): no gain beyond the noise at 4300 vertices, and slower at 48, since the
  segment hierarchy's nearer-first descent finds a near segment at once anyway.
- Remembering recent queries (in a table indexed by the query point's position) with the two
  nearest segments and a lower bound on every other: a query within reach of a remembered one
  then needs two segments instead of its cell's list, with the same answer. 20% of the queries of
  whole runs were answered so, but the bookkeeping made the runs 1.05–1.39× slower.
- Scanning a cell list twice: a distance to every segment without a division (a precomputed
  reciprocal of its squared length), then the exact closest point only for segments within
  rounding of the least. The same answers, 1.13–1.17× slower in three of four cells: the scan
  near Γ is 12–33 segments long (counted in whole runs of Tables 5–7; a query climbs to the
  parent cell in 0.4–14% of the cases), and the second pass and its buffer cost more than the
  divisions they save. A four-wide version with gathered loads was slower still (58 against
  50 ns per query of 21 segments).

Measured and not kept since (each the same answers to the last bit, so only time could decide):

- A deeper or shallower distance tree. Its depth L changes only the cost of a query, never its
  answer, and L = K + P/2 is at or near the least step time: one thread, one step from the
  interface after 16 or 20 steps, Table 5's 40/0/3/1e−3 with P = 0 at L = 3, 4, 5, 6: 0.175,
  0.18, 0.21, 0.26 ms; its 640/0/7/1e−7 with P = 4 at L = 8, 9, 10: 82, 74, 78 ms; Table 7's
  160/2/6/1e−6 with P = 4 at L = 7, 8, 9, 10: 24.9, 22.2, 22.4, 25.4 ms. Deeper trees shorten
  the scans near Γ but not the queries a whole step |kW| from Γ(t), which climb, and cost more to
  build. For the first step, from the 1024-vertex initial polygon, where a tree of depth 3 sends
  every query on that polygon to the segment hierarchy (half of that step), a depth set by the
  polygon's mean segment length took 0.72–1.55 ms against 0.47 ms.
- Root finding one bracket at a time, brackets in parallel (each bracket's iterates in turn on one
  thread, instead of rounds in which all brackets' iterates form one batch of G). One thread: the
  same time. Two threads: 0.91–0.92× at Table 5's 40/0/3/1e−3 with P = 4, 0.95× with P = 0, and
  within the noise (0.98–1.02×) at 160/0/5/1e−5 with P = 2, 320/0/6/1e−6 with P = 4, Table 6's
  80/0/4/1e−4 and 160/0/5/1e−5 with P = 2, and Table 7's 40/1/4/1e−4 with P = 2 and
  320/3/7/1e−7 with P = 4. It would also call G from several threads at once, which the
  contouring module does not ask of a user's G.
- With that order, each kind of query of G (the foot's, the velocity's) keeping what its last
  query found: the four nearest segments of that point x₀ and a radius beyond which every other
  segment lies (the fifth's distance, or the distance to the edge of the cell's triple). A point
  nearer x₀ takes its nearest of the four when that distance plus its distance from x₀ is below
  the radius: the same answer. 62–69% of the queries of the first rows' P = 0 cells were answered
  so, 24–42% in refined cells up to the third row, 5–6% in the finest cells (where most
  evaluations are refinement's midpoints and probes, a segment apart); but keeping the five
  nearest segments in every other query cost about what the short ones saved: Table 5's
  40/0/3/1e−3 with P = 0 0.97×, with P = 4 1.11–1.13×.
- Every parallel loop handing its threads blocks of 8 or of 64 iterations in turn, instead of one
  contiguous block each, for balance where the cost of an iteration varies along a batch: two
  threads, five cells of Tables 5–7 from Table 5's 160/0/5/1e−5 with P = 2 to its 640/0/7/1e−7
  with P = 4, twice each, 0.82–1.27× the current time, slower in 16 of the 20 comparisons.
- Each leaf's list with the segments whose boxes meet the leaf itself first (both parts in
  increasing order), scanned first by a query, which stops there when the box of half-width m
  around x lies in the leaf: the same answer, by the argument for the triple. That part settled
  33% of the queries of whole runs at Table 5's 40/0/3/1e−3 with P = 4 (3.3 segments instead of
  the leaf's 10.7), 45% at its 320/0/6/1e−6 with P = 4 (5.3 of 17.1) and 63% at Table 6's
  160/0/5/1e−5 with P = 2 (5.7 of 17.3); yet one thread, least of repeated whole runs, took
  0.99–1.01× at Table 5's 40/0/3/1e−3 with P = 0 and with P = 4, 0.99× at Table 6's
  160/0/5/1e−5 with P = 2 and 1.01–1.03× at Table 7's 160/2/6/1e−6 with P = 2. The time is in
  the other queries, a step |kW| from Γ(t): per query of Table 5's 40/0/3/1e−3 with P = 4, 9.2
  more segments in 0.6 more lists (leaves away from Γ, and parent cells), and the segment
  hierarchy in 6% of the queries (9.9, 0.58 and 18% at its 320/0/6/1e−6 with P = 4).

Why only changes that keep every result to the last bit: a change in the last bits of the roots
moves single cells' E∞ in Table 6 both ways, where the circles' cusps meet. A smaller root-finding
tolerance, which only makes every root more accurate, shows it: η = 2·10⁻¹¹ instead of 10⁻¹⁰
moves the E∞ of Table 6's first three rows by 0.91–1.11× (40/0/3/1e−3 with P = 3: 0.0322 →
0.0357; 160/0/5/1e−5 with P = 1: 0.0105 → 0.0096), and η = 5·10⁻¹¹ by 0.80–1.00×.
)";
    write_file_atomic(out, md);
    fmt::print(stderr, "wrote {}\n", out);
}
