// Speed per step against the paper and against the step's floor, scaling with the number of
// segments, the speed-up from threads, and runs beside the programs users would pick instead.
// Writes its tables and summaries into their regions of docs/performance.md, a page written by
// hand (doc_regions.hpp), and one line into docs/notes/performance.md; with --check-pages it only
// checks that both pages hold those regions, and with --only zalesak (or curve-shortening) it
// writes that region alone.
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
// Usage: performance_bench [--out FILE] [--notes FILE] [--study DIR] [--reference CSV] [--rows n]
//                          [--prefix n] [--rounds n] [--max-segments n] [--check-pages]
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
#include "doc_regions.hpp"
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

/// Wall time on one thread over wall time on all, for square roots summed in as many parts as
/// threads (each part's sum its own): what the machine's threads give where nothing is shared,
/// which bounds the speed-ups measured for the steps.
double free_speedup() {
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    std::vector<double> sums(cores);
    const auto work = [&] {
        parallel_for(
            cores,
            [&](std::size_t part) {
                double sum = 0.0;
                for (int i = 1; i <= 20'000'000; ++i)
                    sum += std::sqrt(i + static_cast<double>(part));
                sums[part] = sum;
            },
            1);
    };
    set_thread_count(1);
    const Least one = least_of_repeats(work, 0.5, 5);
    set_thread_count(static_cast<int>(cores));
    const Least all = least_of_repeats(work, 0.5, 5);
    set_thread_count(1);
    return one.wall / all.wall;
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
    const char* region;   ///< its table's region of the page
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
        "| N/S/K/ε | P | E ours | E paper | T ours | T paper | paper / ours | T first steps | "
        "G per vertex | step | floor | step / floor | speed-up {} threads |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
        cores);
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
    return md;
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
    return md;
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
    o.step.embedded.smoothing = p.run.step.embedded.smoothing;
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

/// Zalesak's disk, one turn in t = 1: the peers' published rows and ours, and its two figures
/// (error against seconds, the slot's mouth) written into the folder figures.
std::string zalesak_table(const std::filesystem::path& figures) {
    std::filesystem::create_directories(figures);
    std::string md =
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
        zalesak_run("N/K/P/ε = 100/7/4/1e-6, nearest-point extension (default)", 100, 7, 4, 1e-6,
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
    return md;
}

/// Curve shortening of a circle R(0) = 0.5 to t = 0.1, R(t)² = R(0)² − 2t: the peer's published
/// rows and ours, and the figure of error against seconds written into the folder figures. With
/// the embedded module the problem's S = 1 keeps k/h² ≤ 1.6 stable (docs/user-guide.md §5); the
/// arclength module averages over √k, stable at any K.
std::string shortening_table(const std::filesystem::path& figures) {
    std::filesystem::create_directories(figures);
    std::string md =
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
    return md;
}

/// The tables of Tables 5–7, in the order of the page.
constexpr TableSpec tables[] = {
    {"table5_rotation", "propeller-rotation", "table5"},
    {"table6_merging", "merging-circles", "table6"},
    {"table7_curvature", "circle-curvature", "table7"},
};

/// The regions this program writes: of docs/performance.md, and of the notes.
std::vector<std::string> page_regions() {
    std::vector<std::string> names = {"cells-settings", "cells-summary"};
    for (const TableSpec& t : tables) names.emplace_back(t.region);
    for (const char* name : {"scaling", "zalesak", "curve-shortening"}) names.emplace_back(name);
    return names;
}
const std::vector<std::string> notes_regions = {"two-threads-now"};

/// The summaries of the cells over all tables: the paper's time over ours, the floor, the G
/// evaluations and the speed-up.
std::string cells_summary(const Totals& totals) {
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
    std::string md = fmt::format(
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
        "(median {:.0f}×), short of 1000× in {} of {} cells.\n",
        least(totals.paper_over_floor), most(totals.paper_over_floor),
        median(totals.paper_over_floor), floor_short, totals.paper_over_floor.size());
    return md;
}

/// The line of the notes on two threads: the speed-ups now of the step they profile (Table 5's
/// 320/0/6/1e−6 with P = 4) and of Table 6's 160/0/5/1e−5 with P = 2.
std::string two_threads_now(const Totals& totals) {
    // "–" for a cell not timed (fewer --rows).
    const auto speedup = [&](const char* problem, int row, int p) -> std::string {
        const auto it = totals.speedup_of.find({problem, row, p});
        return it == totals.speedup_of.end() ? "–" : fmt::format("{:.2f}×", it->second);
    };
    return fmt::format(
        "Measured now (the tables of [docs/performance.md](../performance.md)): this step's "
        "speed-up on {} threads is {}; Table 6's 160/0/5/1e−5 cell with P = 2 has {} "
        "over its first steps, from the three small circles.\n",
        std::thread::hardware_concurrency(), speedup("propeller-rotation", 3, 4),
        speedup("merging-circles", 2, 2));
}

int run_bench(int argc, char** argv) {
    using slc::bench::take_flag;
    const std::string out = take_flag(argc, argv, "--out", "docs/performance.md");
    const std::string notes = take_flag(argc, argv, "--notes", "docs/notes/performance.md");
    const std::string study_dir = take_flag(argc, argv, "--study", "out/study");
    const std::string reference =
        take_flag(argc, argv, "--reference", "data/paper_convergence_tables.csv");
    const int rows = std::stoi(take_flag(argc, argv, "--rows", "5"));
    const int prefix = std::stoi(take_flag(argc, argv, "--prefix", "16"));
    const int rounds = std::stoi(take_flag(argc, argv, "--rounds", "2"));
    const auto max_segments =
        static_cast<std::size_t>(std::stod(take_flag(argc, argv, "--max-segments", "1e6")));
    if (slc::bench::take_switch(argc, argv, "--check-pages")) {
        bench::check_regions(out, page_regions());
        bench::check_regions(notes, notes_regions);
        fmt::print(stderr, "{} and {} hold every region this program writes\n", out, notes);
        return 0;
    }
    if (rounds < 1) {
        fmt::print(stderr, "performance_bench: --rounds must be at least 1, got {}\n", rounds);
        return 2;
    }
    const auto figures = std::filesystem::path(out).parent_path() / "figures";
    // --only zalesak|curve-shortening: that region alone, in seconds.
    const std::string only = take_flag(argc, argv, "--only", "");
    if (!only.empty()) {
        if (only == "zalesak") {
            bench::write_regions(out, {{"zalesak", zalesak_table(figures)}});
        } else if (only == "curve-shortening") {
            bench::write_regions(out, {{"curve-shortening", shortening_table(figures)}});
        } else {
            fmt::print(stderr,
                       "performance_bench: --only takes zalesak or curve-shortening, got {}\n",
                       only);
            return 2;
        }
        fmt::print(stderr, "wrote {}\n", out);
        return 0;
    }
    // Before two hours of measurements, not after.
    bench::require_regions(out, page_regions());
    bench::require_regions(notes, notes_regions);
    const auto paper = read_reference(reference);

    Totals totals;
    // Rounds: see the comment at the top of this file.
    StudyCells studies[std::size(tables)];
    for (std::size_t t = 0; t < std::size(tables); ++t)
        studies[t] = read_study(fmt::format("{}/{}/table.json", study_dir, tables[t].problem));
    std::vector<CellTimes> times[std::size(tables)];
    double free_least = std::numeric_limits<double>::infinity(), free_most = 0.0;
    for (int round = 0; round < rounds; ++round) {
        const double speedup = free_speedup();
        free_least = std::min(free_least, speedup);
        free_most = std::max(free_most, speedup);
        for (std::size_t t = 0; t < std::size(tables); ++t)
            time_cells(tables[t], rows, prefix, studies[t], round, times[t]);
    }
    const std::string free_low = fmt::format("{:.2f}×", free_least),
                      free_high = fmt::format("{:.2f}×", free_most);
    std::vector<bench::Region> page;
    page.emplace_back(
        "cells-settings",
        fmt::format("Machine: {} hardware threads, which gave {} over one on a loop that shares "
                    "nothing (square roots summed, a sum a thread), measured before each round: "
                    "the most any speed-up below can reach. *T first steps* over the first {} "
                    "steps of each cell; every cell, and every row of the scaling table, timed in "
                    "{} rounds minutes apart.",
                    std::thread::hardware_concurrency(),
                    free_low == free_high ? free_low : free_low + " to " + free_high, prefix,
                    rounds));
    page.emplace_back("cells-summary", "");  // once every table has added to the totals
    for (std::size_t t = 0; t < std::size(tables); ++t)
        page.emplace_back(tables[t].region,
                          cell_table(tables[t], rows, paper, studies[t], times[t], totals));
    page[1].second = cells_summary(totals);
    page.emplace_back("scaling", scaling_table(max_segments, rounds));
    page.emplace_back("zalesak", zalesak_table(figures));
    page.emplace_back("curve-shortening", shortening_table(figures));
    bench::write_regions(out, page);
    bench::write_regions(notes, {{"two-threads-now", two_threads_now(totals)}});
    fmt::print(stderr, "wrote {} and {}\n", out, notes);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    slc::keep_freed_memory();  // as the slc tool does: the timings are the tool's
    try {
        return run_bench(argc, argv);
    } catch (const std::exception& e) {
        fmt::print(stderr, "performance_bench: {}\n", e.what());
        return 1;
    }
}
