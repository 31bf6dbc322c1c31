// slc study: the paper's 5×5 convergence table for a problem with an exact solution (Tables 5–7),
// with observed orders, the paper's numbers beside ours when given, and error against CPU time
// (Fig. 10); or, for the user's curve (--initial), a self-convergence study.
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
#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/io/interface_json.hpp"
#include "slc/io/render.hpp"

namespace slc::cli {
namespace {

struct StudyCommand {
    ProblemSource source;
    std::optional<int> rows;
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
            e_line += fmt::format(" {}{} |", number(cell.e_inf), e_paper);
            t_line += fmt::format(" {:.2e}{} |", cell.cpu_s_per_step, t_paper);
        }
        md += e_line + "\n" + t_line + "\n";
    }
    md +=
        "\n## Observed orders\n\nDown each column (log2 of successive errors; k halves per row: 2 "
        "means second order in time):\n\n| rows | P = 0 | P = 1 | P = 2 | P = 3 | P = 4 "
        "|\n|---|---|---|---|---|---|\n";
    for (int r = 0; r + 1 < s.rows; ++r) {
        md += fmt::format("| {}→{} |", r + 1, r + 2);
        for (int c = 0; c < s.columns; ++c)
            md += fmt::format(" {} |", number(s.column_order(r, c), "{:.2f}"));
        md += "\n";
    }
    md +=
        "\nAlong each row (log2 of successive errors; segments halve per pass: 1 means first "
        "order):\n\n"
        "| row | 0→1 | 1→2 | 2→3 | 3→4 |\n|---|---|---|---|---|\n";
    for (int r = 0; r < s.rows; ++r) {
        md += fmt::format("| {} |", r + 1);
        for (int c = 0; c + 1 < s.columns; ++c)
            md += fmt::format(" {} |", number(s.row_order(r, c), "{:.2f}"));
        md += "\n";
    }
    return md;
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

/// Fig. 10: log10 E_inf against log10 T, a line per row, the paper's rows in grey.
void plot(const std::filesystem::path& dir, const Problem& p, const StudyResult& s,
          const Paper& paper) {
    std::vector<std::vector<Vec2>> ours(static_cast<std::size_t>(s.rows)), theirs(ours.size());
    Box b = Box::empty();
    auto add = [&](std::vector<Vec2>& line, double t, double e) {
        if (!(t > 0) || !(e > 0)) return;
        const Vec2 q{std::log10(t), std::log10(e)};
        line.push_back(q);
        b = unite(b, {q, q});
    };
    for (const StudyCell& c : s.cells) {
        if (c.e_inf) add(ours[static_cast<std::size_t>(c.row)], c.cpu_s_per_step, *c.e_inf);
        auto it = paper.find({c.options.steps, c.refine});
        if (it != paper.end())
            add(theirs[static_cast<std::size_t>(c.row)], it->second.second, it->second.first);
    }
    if (b.is_empty()) return;
    Figure fig(Box::square(b.center(), 0.55 * std::max({b.width(), b.height(), 1.0})),
               fmt::format("{}{}{}: error against CPU time per step", p.name,
                           p.module == GeometryModule::arclength ? ", arclength module" : "",
                           s.rows > 0 && s.at(0, 0).options.step.arcs == true ? ", arcs" : ""));
    fig.set_axis_names("log10 CPU seconds per step", "log10 E_inf");
    for (std::size_t r = 0; r < ours.size(); ++r) {
        if (theirs[r].size() >= 2)
            fig.add_polyline(theirs[r], r == 0 ? "paper" : "", Color{0.6, 0.6, 0.6, 1}, 1.0);
        if (ours[r].size() >= 2) {
            const RunOptions& o = s.at(static_cast<int>(r), 0).options;
            fig.add_polyline(ours[r],
                             fmt::format("ours N = {}, K = {}", o.steps, o.step.contour.depth),
                             palette_color(r));
            fig.add_points(ours[r], palette_color(r), 2.5);
        }
    }
    fig.save(dir / "error_vs_time.svg");
    fig.save(dir / "error_vs_time.png");
}

/// The deepest contouring tree -K accepts.
constexpr int max_depth = 24;

/// --initial: runs at 3..5 resolutions compared with each other.
void run_self_convergence(const StudyCommand& o) {
    const int rows = o.rows.value_or(3);
    if (rows < 3) {
        throw InvalidInput(
            fmt::format("--rows must be 3 to 5 with --initial (runs compared in pairs, and pairs "
                        "for an order), got {}",
                        rows));
    }
    const Problem p = resolve_problem(o.source);
    const RunOptions base = resolve_run_options(o.method, p);
    if (base.step.contour.depth + rows - 1 > max_depth) {
        throw InvalidInput(
            fmt::format("the finest of {} resolutions would have K = {}; K + rows - 1 "
                        "must not exceed {}",
                        rows, base.step.contour.depth + rows - 1, max_depth));
    }
    const std::optional<GeometryModule> module = geometry_module(o.method);
    const auto law = problem_law(p, module ? module : p.module);
    OutputFolder folder(o.out, false);
    write_self_convergence_study(p, *law, base, rows, o.quiet, folder.path());
    folder.commit();
}

void run_study(const StudyCommand& o) {
    apply_threads(o.method.threads);
    if (!o.source.initial.empty()) return run_self_convergence(o);
    if (o.source.problem.empty()) throw InvalidInput("give --problem NAME or --initial FILE");
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
    nlohmann::json cells = nlohmann::json::array();
    for (const StudyCell& c : s.cells) {
        cells.push_back({{"row", c.row + 1},
                         {"run", run_name(c.options)},
                         {"P", c.refine},
                         {"status", to_string(c.status)},
                         {"e_inf", c.e_inf ? nlohmann::json(*c.e_inf) : nlohmann::json(nullptr)},
                         {"cpu_s_per_step", c.cpu_s_per_step},
                         {"g_evals_per_vertex", c.g_evals_per_vertex},
                         {"segments", c.segments}});
    }
    write_file_atomic(
        dir / "table.json",
        nlohmann::json{{"problem", p.name}, {"rows", s.rows}, {"cells", cells}}.dump(2) + "\n");
    plot(dir, p, s, paper);
    folder.commit();
}

}  // namespace

void add_study_command(CLI::App& app) {
    auto o = std::make_shared<StudyCommand>();
    auto* cmd = app.add_subcommand(
        "study",
        "Convergence. --problem NAME: the paper's 5x5 table for a problem with an exact solution "
        "(table.md, table.csv, table.json, error_vs_time.svg/.png). --initial FILE --velocity LAW "
        "--t-end T: self-convergence of your curve, which has none: the run at --rows "
        "resolutions (N doubled, K + 1 and eps / 4 each; the rest as slc run takes it), each "
        "final interface compared with the next (Hausdorff distance at vertices and midpoints), "
        "observed orders, and an estimate of the finest run's error (table.md, table.csv, "
        "table.json, convergence.svg/.png)");
    add_problem_source_options(*cmd, o->source);
    cmd->add_option("--rows", o->rows,
                    "Rows of the table to run, 1..5 (default 5); with --initial the resolutions, "
                    "3..5 (default 3), each costing about 4 times the one before or more")
        ->check(integer_in(1, 5));
    cmd->add_option("--reference", o->reference,
                    "The paper's tables as CSV (table,N,S,K,eps,P,E_inf,T_cpu_s_per_step) to print "
                    "beside ours");
    add_method_options(*cmd, o->method);
    cmd->add_flag("--quiet", o->quiet, "No progress lines");
    cmd->add_option("--out", o->out, "Output folder")->required();
    cmd->callback([o] { run_study(*o); });
}

}  // namespace slc::cli
