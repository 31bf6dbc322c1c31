// slc run: moves an interface — a named problem or the user's curve and velocity law — and writes
// summary.json, final.json, optional frames and pictures.
#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <filesystem>
#include <optional>

#include "commands/commands.hpp"
#include "commands/common.hpp"
#include "commands/run_options.hpp"
#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/geometry/validate.hpp"
#include "slc/io/interface_json.hpp"
#include "slc/io/render.hpp"
#include "slc/io/vtk.hpp"

namespace slc::cli {
namespace {

std::atomic<bool> stop_requested{false};
extern "C" void request_stop(int) { stop_requested = true; }

struct RunCommand {
    std::string problem;
    std::string initial;
    std::string velocity;
    std::optional<double> t_end;
    DomainOptions domain;
    MethodOptions method;
    std::vector<std::string> params;
    std::string geometry;
    int frames = 0;
    bool vtk = false;
    bool quiet = false;
    std::string out;
};

/// The problem to run: a named one, or one assembled from the user's file and law.
Problem resolve_problem(const RunCommand& o) {
    const auto params = parse_params(o.params);
    if (!o.problem.empty()) {
        Problem p = make_problem(o.problem, params);
        if (o.t_end) p.t_end = *o.t_end;
        if (o.domain.half_width || o.domain.box) p.domain = resolve_domain(o.domain, p.initial);
        return p;
    }
    if (o.velocity.empty()) throw InvalidInput("--initial needs --velocity NAME");
    if (!o.t_end) throw InvalidInput("--initial needs --t-end");
    LoadedInterface in = load_interface(o.initial, o.domain);
    Problem p;
    p.name = std::filesystem::path(o.initial).stem().string();
    p.initial = in.curves.curves();
    p.domain = in.domain;
    p.t_start = in.time;
    p.t_end = *o.t_end;
    p.velocity = o.velocity;
    p.velocity_params = params;
    p.steps = 40;
    p.depth = 5;
    p.refine = 2;
    p.eps = 1e-5;
    return p;
}

/// Frames 0..n at evenly spaced steps; frame_path(i) names them.
std::filesystem::path frame_path(const std::filesystem::path& dir, int i) {
    return dir / "frames" / fmt::format("frame_{:04d}.json", i);
}

void draw(const std::filesystem::path& dir, const Problem& p, const Interface& initial,
          const RunResult& r, const std::vector<std::pair<double, Interface>>& frames) {
    Figure final_picture(p.domain,
                         fmt::format("{}: t = {:.4g} ({})", p.name, r.t, to_string(r.status)));
    final_picture.add_curves(initial, "t = 0", Color{0.6, 0.6, 0.6, 1});
    if (!r.curves.empty())
        final_picture.add_curves(r.curves, fmt::format("t = {:.4g}", r.t), palette_color(0));
    final_picture.save(dir / "final.svg");
    final_picture.save(dir / "final.png");
    if (frames.size() < 2) return;
    Figure overlay(p.domain, fmt::format("{}: {} frames", p.name, frames.size()));
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const double along = static_cast<double>(i) / static_cast<double>(frames.size() - 1);
        overlay.add_curves(frames[i].second, fmt::format("t = {:.4g}", frames[i].first),
                           sequence_color(along), 1.0);
    }
    overlay.save(dir / "frames.svg");
    overlay.save(dir / "frames.png");
}

void run_command(const RunCommand& o) {
    apply_threads(o.method.threads);
    const Problem p = resolve_problem(o);
    const RunOptions options = resolve_run_options(o.method, p);
    std::optional<GeometryModule> module = p.module;
    if (!o.geometry.empty())
        module = o.geometry == "embedded" ? GeometryModule::embedded : GeometryModule::intrinsic;
    const auto law = make_velocity(p.velocity, p.velocity_params, module);
    const Interface initial = prepare_interface(p.initial, p.domain).curves;
    const std::filesystem::path dir(o.out);
    std::filesystem::create_directories(dir);

    std::vector<std::pair<double, Interface>> frames;
    auto keep_frame = [&](int i, double t, const Interface& curves) {
        write_file_atomic(frame_path(dir, i), interface_json(curves, t));
        frames.emplace_back(t, curves);
    };
    if (o.frames > 0) keep_frame(0, options.t_start, initial);
    // --vtk: DIR/frames.pvd over DIR/frames/frame_NNNN.vtp — the initial interface, the frames
    // and the final one.
    std::optional<VtkSeries> vtk;
    int vtk_step = 0;
    if (o.vtk) vtk.emplace(dir / "frames.pvd");
    if (vtk) vtk->add(options.t_start, initial);
    const bool progress = !o.quiet && isatty(STDERR_FILENO);
    stop_requested = false;
    std::signal(SIGINT, request_stop);
    std::signal(SIGTERM, request_stop);
    const RunResult r = run(initial, *law, p.domain, options, [&](const StepReport& s) {
        if (o.frames > 0 && (s.step * o.frames) % s.steps < o.frames) {
            keep_frame(static_cast<int>(frames.size()), s.t, *s.curves);
            if (vtk) vtk->add(s.t, *s.curves);
            vtk_step = s.step;
        }
        if (progress && s.wall_s > 2.0) {
            const double left = s.wall_s * (s.steps - s.step) / s.step;
            fmt::print(stderr, "\rstep {}/{}  t = {:.4g}  segments {}  {:.0f} s left   ", s.step,
                       s.steps, s.t, s.curves->size(), left);
        }
        return !stop_requested;
    });
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    if (progress) fmt::print(stderr, "\n");

    write_file_atomic(dir / "final.json", interface_json(r.curves, r.t));
    if (vtk && vtk_step != r.steps_done) vtk->add(r.t, r.curves);
    draw(dir, p, initial, r, frames);
    nlohmann::json summary = run_summary(p, options, r, law->name());
    write_file_atomic(dir / "summary.json", summary.dump(2) + "\n");
    if (!o.quiet) {
        fmt::print("{}: {} at t = {:.6g} after {} steps, e_inf = {}, {:.3g} s cpu; wrote {}\n",
                   p.name, to_string(r.status), r.t, r.steps_done, summary["e_inf"].dump(), r.cpu_s,
                   dir.string());
    }
    if (r.status == RunStatus::error) throw NumericalFailure(r.message);
}

}  // namespace

void add_run_command(CLI::App& app) {
    auto o = std::make_shared<RunCommand>();
    auto* cmd = app.add_subcommand("run",
                                   "Moves an interface: a named problem (--problem) or your curve "
                                   "(--initial) under a velocity law");
    auto* problem = cmd->add_option("--problem", o->problem, problem_help());
    auto* initial = cmd->add_option("--initial", o->initial,
                                    "Interface file (JSON) to move instead of a problem");
    problem->excludes(initial);
    cmd->add_option("--velocity", o->velocity, velocity_help())->excludes(problem);
    cmd->add_option("--param", o->params,
                    "key=value: a parameter of the velocity law or the problem (repeatable)");
    cmd->add_option(
        "--t-end", o->t_end,
        "Final time a (a problem's own by default); with --initial the run starts at the "
        "file's \"time\" (0 if absent)");
    cmd->add_option("--geometry", o->geometry,
                    "Geometry module for normals and curvature: intrinsic or embedded (the law's "
                    "default otherwise)")
        ->check(CLI::IsMember({"intrinsic", "embedded"}));
    add_domain_options(*cmd, o->domain);
    add_method_options(*cmd, o->method);
    cmd->add_option(
           "--frames", o->frames,
           "Write this many frames (plus the initial one) to DIR/frames/ and draw them overlaid")
        ->check(CLI::Range(0, 100000));
    cmd->add_flag("--vtk", o->vtk,
                  "Also write the initial interface, the frames and the final one as VTK PolyData "
                  "(DIR/frames/*.vtp) and DIR/frames.pvd, a time series ParaView opens");
    cmd->add_flag("--quiet", o->quiet, "No progress or closing line");
    cmd->add_option("--out", o->out,
                    "Output folder: summary.json, final.json, final.svg/.png, frames")
        ->required();
    cmd->callback([o, problem, initial] {
        if (problem->count() == 0 && initial->count() == 0)
            throw InvalidInput("give --problem NAME or --initial FILE");
        run_command(*o);
    });
}

}  // namespace slc::cli
