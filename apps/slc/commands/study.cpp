// slc study: the paper's 5×5 convergence table for a problem with an exact solution (Tables 5–7),
// with observed orders, the paper's numbers beside ours when given, and error against CPU time
// (Fig. 10); or, for the user's curve or surface (--initial), a self-convergence study.
#include "slc/evolve/study.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "commands/commands.hpp"
#include "commands/common.hpp"
#include "commands/output_folder.hpp"
#include "commands/problem_source.hpp"
#include "commands/run_options.hpp"
#include "commands/self_convergence.hpp"
#include "commands/surface_run.hpp"
#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/evolve/surface_study.hpp"
#include "slc/io/interface_json.hpp"
#include "slc/io/render.hpp"
#include "slc/io/surface_files.hpp"
#include "slc/tree/tetrahedralization.hpp"

namespace slc::cli {
namespace {

struct StudyCommand {
    ProblemSource source;
    std::optional<int> rows;
    std::optional<int> columns;
    std::string reference;
    MethodOptions method;
    bool quiet = false;
    std::string out;
};

/// The paper's (E_inf, T) by (N, P) for one of its tables, from its reference CSV
/// (table,N,S,K,eps,P,E_inf,T_cpu_s_per_step).
using Paper = std::map<std::pair<int, int>, std::pair<double, double>>;

Paper read_reference(const std::string& path, const std::string& table) {
    Paper paper;
    if (path.empty() || table.empty()) return paper;
    std::ifstream in(path);
    if (!in) throw InvalidInput(fmt::format("cannot read {}", path));
    std::string line;
    while (std::getline(in, line)) {
        std::vector<std::string> f;
        std::stringstream row(line);
        for (std::string field; std::getline(row, field, ',');) f.push_back(field);
        if (f.size() != 8 || f[0] != table) continue;
        paper[{std::stoi(f[1]), std::stoi(f[5])}] = {std::stod(f[6]), std::stod(f[7])};
    }
    return paper;
}

std::string number(const std::optional<double>& v, const char* format = "{:.3g}") {
    return v ? fmt::format(fmt::runtime(format), *v) : "—";
}

/// The observed orders of a study's table, as markdown: down each column and along each row.
template <class Result>
std::string orders_markdown(const Result& s, const std::string& along_note) {
    std::string header = "|", rule = "|---|";
    for (int c = 0; c < s.columns; ++c) {
        header += fmt::format(" P = {} |", c);
        rule += "---|";
    }
    std::string md = fmt::format(
        "\n## Observed orders\n\nDown each column (log2 of successive errors; k halves per "
        "row: 2 means second order in time):\n\n| rows {}\n{}\n",
        header, rule);
    for (int r = 0; r + 1 < s.rows; ++r) {
        md += fmt::format("| {}→{} |", r + 1, r + 2);
        for (int c = 0; c < s.columns; ++c)
            md += fmt::format(" {} |", number(s.column_order(r, c), "{:.2f}"));
        md += "\n";
    }
    md += fmt::format("\nAlong each row (log2 of successive errors; {}):\n\n| row |", along_note);
    std::string along_rule = "|---|";
    for (int c = 0; c + 1 < s.columns; ++c) {
        md += fmt::format(" {}→{} |", c, c + 1);
        along_rule += "---|";
    }
    md += "\n" + along_rule + "\n";
    for (int r = 0; r < s.rows; ++r) {
        md += fmt::format("| {} |", r + 1);
        for (int c = 0; c + 1 < s.columns; ++c)
            md += fmt::format(" {} |", number(s.row_order(r, c), "{:.2f}"));
        md += "\n";
    }
    return md;
}

std::string markdown(const Problem& p, const StudyResult& s, const Paper& paper) {
    std::string md = fmt::format("# Convergence study: {}\n\n{}\n\n", p.name, p.description);
    const int threads = thread_count();
    md += fmt::format(
        "E_inf is the largest |exact signed distance| over the final vertices and segment "
        "midpoints (paper Eq. 11); T is process CPU seconds per step, on {} thread{}. Rows refine "
        "N, K and ε together; columns add passes P of adaptive refinement.",
        threads, threads == 1 ? "" : "s");
    if (p.module == GeometryModule::arclength)
        md += " Curvature from the arclength geometry module (--geometry arclength).";
    if (s.rows > 0 && s.at(0, 0).options.step.arcs == true)
        md += " G reads the curves as arcs through their vertices (--arcs).";
    if (!paper.empty()) md += " Each cell: ours / the paper's (450 MHz UltraSPARC II, 2000).";
    md +=
        "\n\n| N/S/K/ε | | P = 0 | P = 1 | P = 2 | P = 3 | P = 4 "
        "|\n|---|---|---|---|---|---|---|\n";
    for (int r = 0; r < s.rows; ++r) {
        const RunOptions& o = s.at(r, 0).options;
        std::string e_line =
            fmt::format("| {}/{}/{}/{:.0e} | E_inf |", o.steps, o.step.embedded.smoothing,
                        o.step.contour.depth, o.step.contour.resolved_eps());
        std::string t_line = "| | T |";
        for (int c = 0; c < s.columns; ++c) {
            const StudyCell& cell = s.at(r, c);
            auto it = paper.find({o.steps, c});
            const std::string e_paper =
                it == paper.end() ? "" : fmt::format(" / {:.3g}", it->second.first);
            const std::string t_paper =
                it == paper.end() ? "" : fmt::format(" / {:.3g}", it->second.second);
            e_line +=
                fmt::format(" {}{}{} |", cell.e_inf ? number(cell.e_inf) : to_string(cell.status),
                            cell.stopped.empty() ? "" : "*", e_paper);
            t_line += fmt::format(" {:.2e}{} |", cell.cpu_s_per_step, t_paper);
        }
        md += e_line + "\n" + t_line + "\n";
    }
    std::string stopped;
    for (const StudyCell& c : s.cells)
        if (!c.stopped.empty())
            stopped += fmt::format("- {}/{}/{}/{}: {}\n", c.options.steps,
                                   c.options.step.embedded.smoothing, c.options.step.contour.depth,
                                   c.refine, c.stopped);
    if (!stopped.empty())
        md +=
            "\n\\* The guards stop these runs; the cell is the same run without them "
            "(`--no-guards`), as the paper's runs are, to its end (status broken):\n\n" +
            stopped;
    md += orders_markdown(s, "segments halve per pass: 1 means first order");
    return md;
}

/// The cells of table.json, an object each: the keys of both dimensions (row, from 1, P, status,
/// e_inf, cpu_s_per_step) added to own(c), the dimension's own.
template <class Cell, class Own>
nlohmann::json cells_json(const std::vector<Cell>& cells, Own own) {
    nlohmann::json out = nlohmann::json::array();
    for (const Cell& c : cells) {
        nlohmann::json j = own(c);
        j["row"] = c.row + 1;
        j["P"] = c.refine;
        j["status"] = to_string(c.status);
        j["e_inf"] = c.e_inf ? nlohmann::json(*c.e_inf) : nlohmann::json(nullptr);
        j["cpu_s_per_step"] = c.cpu_s_per_step;
        out.push_back(std::move(j));
    }
    return out;
}

std::string csv(const StudyResult& s) {
    std::string out = "row,N,S,K,eps,P,status,E_inf,T_cpu_s_per_step,g_evals_per_vertex,segments\n";
    for (const StudyCell& c : s.cells) {
        const auto& o = c.options;
        out += fmt::format("{},{},{},{},{:.0e},{},{},{},{:.6g},{:.4g},{}\n", c.row + 1, o.steps,
                           o.step.embedded.smoothing, o.step.contour.depth,
                           o.step.contour.resolved_eps(), c.refine, to_string(c.status),
                           c.e_inf ? fmt::format("{:.6g}", *c.e_inf) : "", c.cpu_s_per_step,
                           c.g_evals_per_vertex, c.segments);
    }
    return out;
}

/// One line of an error-against-time plot: (CPU seconds per step, E_inf) pairs.
struct ErrorLine {
    std::string label;
    std::vector<Vec2> points;
};

/// Fig. 10: log10 E_inf against log10 T, a line per row, the paper's rows (`grey`) in grey.
void plot_error_vs_time(const std::filesystem::path& dir, const std::string& title,
                        std::vector<ErrorLine> ours, std::vector<ErrorLine> grey) {
    Box b = Box::empty();
    for (auto* lines : {&ours, &grey}) {
        for (ErrorLine& line : *lines) {
            std::vector<Vec2> logs;
            for (const Vec2 p : line.points) {
                if (!(p.x > 0) || !(p.y > 0)) continue;
                logs.push_back({std::log10(p.x), std::log10(p.y)});
                b = unite(b, {logs.back(), logs.back()});
            }
            line.points = std::move(logs);
        }
    }
    if (b.is_empty()) return;
    Figure fig(Box::square(b.center(), 0.55 * std::max({b.width(), b.height(), 1.0})), title);
    fig.set_axis_names("log10 CPU seconds per step", "log10 E_inf");
    for (std::size_t r = 0; r < grey.size(); ++r) {
        if (grey[r].points.size() >= 2)
            fig.add_polyline(grey[r].points, grey[r].label, Color{0.6, 0.6, 0.6, 1}, 1.0);
    }
    for (std::size_t r = 0; r < ours.size(); ++r) {
        if (ours[r].points.size() >= 2) {
            fig.add_polyline(ours[r].points, ours[r].label, palette_color(r));
            fig.add_points(ours[r].points, palette_color(r), 2.5);
        }
    }
    fig.save(dir / "error_vs_time.svg");
    fig.save(dir / "error_vs_time.png");
}

/// Fig. 10 for a study of curves, the paper's rows beside ours.
void plot(const std::filesystem::path& dir, const Problem& p, const StudyResult& s,
          const Paper& paper) {
    std::vector<ErrorLine> ours(static_cast<std::size_t>(s.rows)), theirs(ours.size());
    for (std::size_t r = 0; r < ours.size(); ++r) {
        const RunOptions& o = s.at(static_cast<int>(r), 0).options;
        ours[r].label = fmt::format("ours N = {}, K = {}", o.steps, o.step.contour.depth);
        theirs[r].label = r == 0 ? "paper" : "";
    }
    for (const StudyCell& c : s.cells) {
        if (c.e_inf)
            ours[static_cast<std::size_t>(c.row)].points.push_back({c.cpu_s_per_step, *c.e_inf});
        auto it = paper.find({c.options.steps, c.refine});
        if (it != paper.end()) {
            theirs[static_cast<std::size_t>(c.row)].points.push_back(
                {it->second.second, it->second.first});
        }
    }
    plot_error_vs_time(
        dir,
        fmt::format("{}{}{}: error against CPU time per step", p.name,
                    p.module == GeometryModule::arclength ? ", arclength module" : "",
                    s.rows > 0 && s.at(0, 0).options.step.arcs == true ? ", arcs" : ""),
        std::move(ours), std::move(theirs));
}

/// The table of a study of surfaces, as markdown.
std::string surface_markdown(const SurfaceProblem& p, const SurfaceStudyResult& s) {
    const int threads = thread_count();
    std::string md = fmt::format(
        "# Convergence study: {}\n\n{}\n\nE_inf is the largest |exact signed distance| over "
        "the final vertices and triangle centroids; T is process CPU seconds per step, on {} "
        "thread{}. Rows refine N, K and ε together (N doubled, K + 1, ε / 4); columns add "
        "passes P of adaptive refinement (the initial surface is contoured with the same K, P "
        "and ε). Triangles: of the final surface.\n\n| N/K/ε | |",
        p.name, p.description, threads, threads == 1 ? "" : "s");
    std::string rule = "|---|---|";
    for (int c = 0; c < s.columns; ++c) {
        md += fmt::format(" P = {} |", c);
        rule += "---|";
    }
    md += "\n" + rule + "\n";
    for (int r = 0; r < s.rows; ++r) {
        const SurfaceRunOptions& o = s.at(r, 0).options;
        std::string e_line = fmt::format("| {}/{}/{:.2g} | E_inf |", o.steps, o.step.contour.depth,
                                         o.step.contour.resolved_eps());
        std::string t_line = "| | T |", n_line = "| | triangles |";
        for (int c = 0; c < s.columns; ++c) {
            const SurfaceStudyCell& cell = s.at(r, c);
            e_line += cell.status == RunStatus::ok ? fmt::format(" {} |", number(cell.e_inf))
                                                   : fmt::format(" {} |", to_string(cell.status));
            t_line += fmt::format(" {:.2e} |", cell.cpu_s_per_step);
            n_line += fmt::format(" {} |", cell.triangles);
        }
        md += e_line + "\n" + t_line + "\n" + n_line + "\n";
    }
    return md + orders_markdown(s, "triangle edges halve per pass: 2 means second order");
}

std::string surface_csv(const SurfaceStudyResult& s) {
    std::string out =
        "row,N,K,eps,P,status,E_inf,T_cpu_s_per_step,wall_s,initial_triangles,triangles\n";
    for (const SurfaceStudyCell& c : s.cells) {
        const auto& o = c.options;
        out += fmt::format("{},{},{},{:.6g},{},{},{},{:.6g},{:.6g},{},{}\n", c.row + 1, o.steps,
                           o.step.contour.depth, o.step.contour.resolved_eps(), c.refine,
                           to_string(c.status), c.e_inf ? fmt::format("{:.6g}", *c.e_inf) : "",
                           c.cpu_s_per_step, c.wall_s, c.initial_triangles, c.triangles);
    }
    return out;
}

/// slc study --problem NAME for a problem of surfaces.
void run_surface_study(const StudyCommand& o) {
    const MethodOptions& m = o.method;
    const std::vector<std::pair<bool, const char*>> fixed = {
        {m.settings.steps.has_value(), "-N/--steps"},
        {m.settings.depth.has_value(), "-K/--depth"},
        {m.settings.refine.has_value(), "-P/--refine"},
        {m.settings.eps.has_value(), "--eps"},
        {m.settings.eta.has_value(), "--eta"},
        {m.settings.mesh.has_value(), "--mesh"},
        {m.settings.smoothing.has_value(), "-S/--smooth"},
        {m.settings.tree_depth.has_value(), "-L/--tree-depth"},
        {m.extension.has_value(), "--extension"},
        {!m.geometry.empty(), "--geometry"},
        {m.settings.arcs.has_value(), "--arcs"},
        {m.settings.area_correction.has_value(), "--area-correction"},
        {m.settings.arc_width.has_value(), "--arc-width"},
        {!o.reference.empty(), "--reference"},
        {!o.source.params.empty(), "--param"},
        {o.source.t_end.has_value(), "--t-end"}};
    for (const auto& [given, name] : fixed) {
        if (given) {
            throw InvalidInput(fmt::format(
                "{} does not apply to the study of a surface, whose table sets every run", name));
        }
    }
    if (o.source.domain.half_width || o.source.domain.box)
        throw InvalidInput("--domain and --box do not apply to the study of a surface");
    const SurfaceProblem p = make_surface_problem(o.source.problem);
    if (!p.study) {
        throw InvalidInput(
            fmt::format("problem '{}' has no convergence study; studies: sphere-rotation, "
                        "sphere-curvature, merging-spheres",
                        p.name));
    }
    OutputFolder folder(o.out, false);
    const SurfaceStudyResult s =
        surface_study(p, o.rows.value_or(3), o.columns.value_or(4), [&](const SurfaceStudyCell& c) {
            if (!o.quiet) {
                fmt::print(stderr, "N {} K {} eps {:.2g}  P = {}: {}, E_inf = {}, {:.3g} s/step\n",
                           c.options.steps, c.options.step.contour.depth,
                           c.options.step.contour.resolved_eps(), c.refine, to_string(c.status),
                           number(c.e_inf), c.cpu_s_per_step);
            }
        });
    const std::filesystem::path dir = folder.path();
    write_file_atomic(dir / "table.md", surface_markdown(p, s));
    write_file_atomic(dir / "table.csv", surface_csv(s));
    const nlohmann::json cells = cells_json(s.cells, [](const SurfaceStudyCell& c) {
        return nlohmann::json{{"N", c.options.steps},
                              {"K", c.options.step.contour.depth},
                              {"eps", c.options.step.contour.resolved_eps()},
                              {"wall_s", c.wall_s},
                              {"triangles", c.triangles}};
    });
    nlohmann::json orders = nlohmann::json::object();
    auto json_orders = [&](auto order, int rows, int columns) {
        nlohmann::json out = nlohmann::json::array();
        for (int r = 0; r < rows; ++r) {
            nlohmann::json line = nlohmann::json::array();
            for (int c = 0; c < columns; ++c) {
                const std::optional<double> q = order(r, c);
                line.push_back(q ? nlohmann::json(*q) : nlohmann::json(nullptr));
            }
            out.push_back(line);
        }
        return out;
    };
    orders["down_columns"] =
        json_orders([&](int r, int c) { return s.column_order(r, c); }, s.rows - 1, s.columns);
    orders["along_rows"] =
        json_orders([&](int r, int c) { return s.row_order(r, c); }, s.rows, s.columns - 1);
    write_file_atomic(dir / "table.json", nlohmann::json{{"problem", p.name},
                                                         {"rows", s.rows},
                                                         {"columns", s.columns},
                                                         {"cells", cells},
                                                         {"orders", orders}}
                                                  .dump(2) +
                                              "\n");
    std::vector<ErrorLine> lines(static_cast<std::size_t>(s.rows));
    for (const SurfaceStudyCell& c : s.cells) {
        ErrorLine& line = lines[static_cast<std::size_t>(c.row)];
        line.label = fmt::format("N = {}, K = {}", c.options.steps, c.options.step.contour.depth);
        if (c.e_inf) line.points.push_back({c.cpu_s_per_step, *c.e_inf});
    }
    plot_error_vs_time(dir, fmt::format("{}: error against CPU time per step", p.name),
                       std::move(lines), {});
    folder.commit();
}

/// The deepest contouring tree -K accepts.
constexpr int max_depth = 24;

/// --rows with --initial, 3..5 (default 3): InvalidInput for fewer, or for a finest run of a
/// depth K + rows − 1 beyond `deepest`.
int self_convergence_rows(const StudyCommand& o, int depth, int deepest) {
    const int rows = o.rows.value_or(3);
    if (rows < 3) {
        throw InvalidInput(
            fmt::format("--rows must be 3 to 5 with --initial (runs compared in pairs, and pairs "
                        "for an order), got {}",
                        rows));
    }
    if (depth + rows - 1 > deepest) {
        throw InvalidInput(
            fmt::format("the finest of {} resolutions would have K = {}; K + rows - 1 "
                        "must not exceed {}",
                        rows, depth + rows - 1, deepest));
    }
    return rows;
}

/// --initial: runs at 3..5 resolutions compared with each other.
void run_self_convergence(const StudyCommand& o) {
    const Problem p = resolve_problem(o.source);
    const RunOptions base = resolve_run_options(o.method, p);
    const int rows = self_convergence_rows(o, base.step.contour.depth, max_depth);
    const std::optional<GeometryModule> module = geometry_module(o.method);
    const auto law = problem_law(p, module ? module : p.module);
    OutputFolder folder(o.out, false);
    write_self_convergence_study(p, *law, base, rows, o.quiet, folder.path());
    folder.commit();
}

/// --initial with a surface: runs at 3..5 resolutions compared with each other.
void run_surface_self_convergence(const StudyCommand& o) {
    const MethodOptions& m = o.method;
    // The settings of curves among the method options are refused by apply_overrides.
    const std::vector<std::pair<bool, const char*>> curve_only = {
        {o.source.field_file.has_value(), "--field-file"},
        {!m.geometry.empty(), "--geometry"},
        {!o.reference.empty(), "--reference"},
        {o.columns.has_value(), "--columns"}};
    for (const auto& [given, name] : curve_only) {
        if (given) {
            throw InvalidInput(
                fmt::format("{} does not apply to the self-convergence study of a surface", name));
        }
    }
    SurfaceRunRequest request;
    request.initial = o.source.initial;
    request.velocity = o.source.velocity;
    request.speed = o.source.speed;
    request.field = o.source.field;
    request.params = o.source.params;
    request.t_end = o.source.t_end;
    request.domain = o.source.domain;
    request.settings = overrides_of(m);
    const SurfaceRunSetup setup = resolve_surface_run(request);
    const int rows =
        self_convergence_rows(o, setup.options.step.contour.depth, max_tetrahedralized_depth);
    OutputFolder folder(o.out, false);
    const SurfaceLawText law{o.source.speed   ? "speed"
                             : o.source.field ? "field"
                                              : o.source.velocity,
                             o.source.speed ? *o.source.speed : o.source.field.value_or(""),
                             parse_params(o.source.params)};
    write_surface_self_convergence_study(setup.problem, law, setup.options, rows, o.quiet,
                                         folder.path());
    folder.commit();
}

void run_study(const StudyCommand& o) {
    apply_threads(o.method.threads);
    if (!o.source.initial.empty()) {
        if (is_surface_file(o.source.initial)) return run_surface_self_convergence(o);
        if (o.columns) throw InvalidInput("--columns is for the study of a surface");
        return run_self_convergence(o);
    }
    if (o.source.problem.empty()) throw InvalidInput("give --problem NAME or --initial FILE");
    if (is_surface_problem(o.source.problem)) return run_surface_study(o);
    if (o.columns) throw InvalidInput("--columns is for the study of a surface");
    Problem p = resolve_problem(o.source);
    if (const auto module = geometry_module(o.method)) p.module = module;
    if (!p.exact)
        throw InvalidInput(
            fmt::format("problem '{}' has no exact solution to measure errors against", p.name));
    const RunOptions base = resolve_run_options(o.method, p);
    const Paper paper = read_reference(o.reference, p.study.paper_table);
    OutputFolder folder(o.out, false);
    const StudyResult s = study(p, o.rows.value_or(5), base, [&](const StudyCell& c) {
        if (!o.quiet) {
            fmt::print(stderr, "{}  P = {}: E_inf = {}, {:.3g} s/step\n", run_name(c.options),
                       c.refine, number(c.e_inf), c.cpu_s_per_step);
        }
    });
    const std::filesystem::path dir = folder.path();
    write_file_atomic(dir / "table.md", markdown(p, s, paper));
    write_file_atomic(dir / "table.csv", csv(s));
    const nlohmann::json cells = cells_json(s.cells, [](const StudyCell& c) {
        return nlohmann::json{{"run", run_name(c.options)},
                              {"g_evals_per_vertex", c.g_evals_per_vertex},
                              {"segments", c.segments},
                              {"stopped_by_guards", c.stopped.empty() ? nlohmann::json(nullptr)
                                                                      : nlohmann::json(c.stopped)}};
    });
    write_file_atomic(
        dir / "table.json",
        nlohmann::json{{"problem", p.name}, {"rows", s.rows}, {"cells", cells}}.dump(2) + "\n");
    plot(dir, p, s, paper);
    folder.commit();
}

}  // namespace

void add_study_command(CLI::App& app) {
    const auto [cmd, o] =
        add_command<StudyCommand>(app, "study",
                                  "Convergence: the paper's 5x5 table of a named problem, or the "
                                  "self-convergence of your curve or surface");
    add_problem_source_options(*cmd, o->source);
    cmd->add_option("--rows", o->rows,
                    "Rows of the table to run, 1..5 (default 5); with --initial the resolutions, "
                    "3..5 (default 3), each costing about 4 times the one before or more (a "
                    "surface's about 8 times); for a surface problem 1..5 (default 3), each "
                    "costing about 8 times the one before")
        ->check(integer_in(1, 5));
    cmd->add_option("--columns", o->columns,
                    "For a surface: columns P = 0 .. C - 1 of passes of refinement, 1..5 "
                    "(default 4)")
        ->check(integer_in(1, 5));
    cmd->add_option("--reference", o->reference,
                    "The paper's tables as CSV (table,N,S,K,eps,P,E_inf,T_cpu_s_per_step) to print "
                    "beside ours");
    add_method_options(*cmd, o->method);
    cmd->add_flag("--quiet", o->quiet, "No progress lines");
    cmd->add_option("--out", o->out, "Output folder")->required();
    cmd->footer(
        "--problem NAME: the paper's table for a problem with an exact solution (table.md, "
        "table.csv,\ntable.json, error_vs_time.svg/.png); for a problem of surfaces "
        "(sphere-rotation,\nsphere-curvature, merging-spheres) --rows x --columns of "
        "it.\n\n--initial FILE --velocity LAW --t-end T: your curve or surface (.obj, .stl, .ply, "
        ".vdb), which\nhas no exact solution, run at --rows resolutions (N doubled, K + 1 and eps "
        "/ 4 each; the rest as\nslc run takes it), each final interface compared with the next "
        "(Hausdorff distance at vertices\nand segment midpoints, or triangle centroids): observed "
        "orders and an estimate of the finest\nrun's error (table.md, table.csv, table.json, "
        "convergence.svg/.png, final_r.json or\nfinal_r.obj).");
    cmd->callback([o] { run_study(*o); });
}

}  // namespace slc::cli
