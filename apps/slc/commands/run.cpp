// slc run: moves an interface — a named problem or the user's curve and velocity law — and writes
// summary.json, final.json, the history of area and length, optional frames and pictures.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <optional>

#include "commands/checkpoint.hpp"
#include "commands/commands.hpp"
#include "commands/common.hpp"
#include "commands/history.hpp"
#include "commands/memory_budget.hpp"
#include "commands/output_folder.hpp"
#include "commands/problem_source.hpp"
#include "commands/run_options.hpp"
#include "commands/surface_run.hpp"
#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/stop.hpp"
#include "slc/evolve/self_convergence.hpp"
#include "slc/geometry/validate.hpp"
#include "slc/io/interface_json.hpp"
#include "slc/io/render.hpp"
#include "slc/io/vdb.hpp"
#include "slc/io/vtk.hpp"

namespace slc::cli {
namespace {

std::atomic<bool> stop_requested{false};
std::atomic<int> stop_signal{0};
/// The first SIGINT or SIGTERM stops the run at the next stage of its step (slc/core/stop.hpp),
/// which then writes its results whole (status interrupted, the last whole step); a second one
/// ends the process at once (the output folder keeps the results it held before).
extern "C" void on_stop_signal(int signal) {
    stop_requested = true;
    stop_signal = signal;
    slc::request_stop();
    std::signal(signal, SIG_DFL);
}

/// Ctrl-C and SIGTERM handled from the start of a run to the end of its writes.
class StopSignals {
public:
    StopSignals() {
        stop_requested = false;
        stop_signal = 0;
        clear_stop();
        std::signal(SIGINT, on_stop_signal);
        std::signal(SIGTERM, on_stop_signal);
    }
    ~StopSignals() {
        std::signal(SIGINT, SIG_DFL);
        std::signal(SIGTERM, SIG_DFL);
    }
    StopSignals(const StopSignals&) = delete;
    StopSignals& operator=(const StopSignals&) = delete;
};

struct RunCommand {
    ProblemSource source;
    MethodOptions method;
    int frames = 0;
    std::optional<std::string> view;
    bool vtk = false;
    bool quiet = false;
    std::string out;
    int checkpoint_every = 0;
    std::string resume;
    bool estimate = false;
    std::optional<double> volume_drift;
    bool no_guards = false;
    std::optional<int> until_components;
    bool vdb = false;
    std::optional<double> vdb_voxel;
};

/// Frames 0..n at evenly spaced steps; frame_path(i) names them.
std::filesystem::path frame_path(const std::filesystem::path& dir, int i) {
    return dir / "frames" / fmt::format("frame_{:04d}.json", i);
}

void draw(const std::filesystem::path& dir, const Problem& p, const Interface& initial,
          const RunResult& r, const std::vector<std::pair<double, Interface>>& frames,
          int frames_written) {
    // The domain, and when it grew, what the curves drawn reached beyond it.
    Box view = p.domain;
    if (r.domain_doublings > 0) {
        Box reached = bounding_box(r.curves.points());
        for (const auto& frame : frames)
            reached = unite(reached, bounding_box(frame.second.points()));
        if (!reached.is_empty()) view = unite(view, reached.inflated(0.05 * reached.width()));
    }
    Figure final_picture(view,
                         fmt::format("{}: t = {:.4g} ({})", p.name, r.t, to_string(r.status)));
    final_picture.add_curves(initial, "t = 0", Color{0.6, 0.6, 0.6, 1});
    if (!r.curves.empty())
        final_picture.add_curves(r.curves, fmt::format("t = {:.4g}", r.t), palette_color(0));
    final_picture.save(dir / "final.svg");
    final_picture.save(dir / "final.png");
    if (frames.size() < 2) return;
    // Colour runs with time; the legend names at most legend_frames of them, evenly spread from
    // the first to the last (a legend line per frame would make the picture as tall as the
    // frames are many, beyond what cairo can draw from about 1600 frames).
    constexpr std::size_t legend_frames = 9;
    const std::size_t last = frames.size() - 1;
    const std::size_t labelled = std::min(frames.size(), legend_frames);
    std::vector<char> named(frames.size(), 0);
    for (std::size_t j = 0; j < labelled; ++j)
        named[(j * last + (labelled - 1) / 2) / (labelled - 1)] = 1;
    const std::string shown = frames.size() == static_cast<std::size_t>(frames_written)
                                  ? fmt::format("{} frames", frames_written)
                                  : fmt::format("{} of {} frames", frames.size(), frames_written);
    // A run that did not end ok says so, with where it stopped.
    const std::string ending = r.status == RunStatus::ok
                                   ? ""
                                   : fmt::format(", {} at t = {:.4g}", to_string(r.status), r.t);
    Figure overlay(view, fmt::format("{}: {}{}", p.name, shown, ending));
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const double along = static_cast<double>(i) / static_cast<double>(last);
        overlay.add_curves(frames[i].second,
                           named[i] ? fmt::format("t = {:.4g}", frames[i].first) : std::string(),
                           sequence_color(along), 1.0);
    }
    overlay.save(dir / "frames.svg");
    overlay.save(dir / "frames.png");
}

/// The frames the overlay picture shows: every stride-th frame from the first, and the last one
/// added, so that at most max_shown + 1 interfaces are held however many frames the run writes
/// (thousands of whole interfaces could take gigabytes, and draw a picture nobody can read).
class OverlayFrames {
public:
    static constexpr int max_shown = 64;

    /// For a run that writes `frames` frames in all (the initial one included).
    explicit OverlayFrames(int frames)
        : stride_(std::max(1, (frames + max_shown - 1) / max_shown)) {}

    /// The next frame, at time t.
    void add(double t, const Interface& curves) {
        if (count_ % stride_ == 0) {
            kept_.emplace_back(t, curves);
            latest_.reset();
        } else {
            latest_.emplace(t, curves);
        }
        ++count_;
    }
    /// The frames to draw, in order.
    std::vector<std::pair<double, Interface>> shown() const {
        std::vector<std::pair<double, Interface>> out = kept_;
        if (latest_) out.push_back(*latest_);
        return out;
    }
    /// Frames added so far.
    int count() const { return count_; }

private:
    int stride_;
    int count_ = 0;
    std::vector<std::pair<double, Interface>> kept_;
    std::optional<std::pair<double, Interface>> latest_;
};

/// Refuses K or L (= K + P unless given) beyond the machine's memory for the initial curves.
void check_run_memory(const RunOptions& options, const Interface& initial, const Box& domain) {
    const double l = length(initial);
    const int k = options.step.contour.depth;
    const int tree = options.step.resolved_tree_depth();
    check_tree_memory(fmt::format("--depth {}", k), k, l, domain.width(), run_bytes_per_cell);
    check_tree_memory(fmt::format("--tree-depth {}", tree), tree, l, domain.width(),
                      distance_bytes_per_cell);
}

/// The settings of a run: the method options, the guards, the frames (a user's run without -N
/// takes a multiple of them) and (a surface's) the volume drift.
RunOverrides run_settings(const RunCommand& o) {
    RunOverrides q = overrides_of(o.method);
    if (o.frames > 0) q.frames = o.frames;
    q.volume_drift = o.volume_drift;
    if (o.no_guards) q.guards = false;
    if (o.until_components) q.until_components = static_cast<std::size_t>(*o.until_components);
    return q;
}

/// Runs o from the start, or from a checkpoint, writing into folder; `given` are the options to
/// store in checkpoints, `id` the run's identity (run_id).
void run_command(const RunCommand& o, const std::vector<GivenOption>& given, const std::string& id,
                 const Checkpoint* from, OutputFolder& folder) {
    apply_threads(o.method.threads);
    const Problem p = resolve_problem(o.source);
    const RunOptions options = run_options(p, run_settings(o), SettingNames::tool);
    // --estimate's run at half resolution, resolved first so that one it cannot have (N or K
    // of 1) is an input error before anything runs.
    if (o.estimate) require_half_resolution(options.steps, options.step.contour.depth);
    const std::optional<RunOptions> coarse =
        o.estimate ? std::optional(resolution_options(options, -1)) : std::nullopt;
    const std::optional<GeometryModule> module = geometry_module(o.method);
    const auto law = problem_law(p, module ? module : p.module);
    const Interface initial = prepare_interface(p.initial, p.domain).curves;
    check_run_memory(options, initial, p.domain);
    if (from) check_checkpoint(*from, p.domain, options, folder.target());
    const std::filesystem::path dir = folder.path();
    // DIR/history.csv: written now, at each checkpoint and at the end; on --resume read back first,
    // so that a history that cannot be continued stops the run before anything is written.
    History history(dir);
    if (from) {
        history.resume(from->state.steps_done, from->state.t, folder.target() / "history.csv");
    } else {
        history.start(options.t_start, initial);
        history.save_csv();
    }

    // --vtk: DIR/frames.pvd over DIR/frames/frame_NNNN.vtp — the initial interface (or, after
    // --resume, the frames kept so far), the frames and the final one.
    std::optional<VtkSeries> vtk;
    int vtk_step = 0;
    if (o.vtk) vtk.emplace(dir / "frames.pvd");
    OverlayFrames overlay(o.frames > 0 ? o.frames + 1 : 0);
    auto keep_frame = [&](double t, const Interface& curves) {
        write_file_atomic(frame_path(dir, overlay.count()), interface_json(curves, t));
        overlay.add(t, curves);
        if (vtk) vtk->add(t, curves);
    };
    if (from) {  // the frames a checkpointed run wrote before it stopped, read back one by one
        for (int i = 0; i < from->frames_kept; ++i) {
            const InterfaceFile f = read_interface_json(frame_path(folder.target(), i));
            const Interface curves(f.curves);
            overlay.add(f.time, curves);
            if (vtk) vtk->add(f.time, curves);
        }
    } else if (o.frames > 0) {
        keep_frame(options.t_start, initial);
    }
    if (vtk && overlay.count() == 0) vtk->add(options.t_start, initial);
    const bool progress = !o.quiet && isatty(STDERR_FILENO);
    const Observer observer = [&](const StepReport& s) {
        history.add(s.t, *s.curves, s.step_cpu_s);
        if (o.frames > 0 && (std::int64_t{s.step} * o.frames) % s.steps < o.frames) {
            keep_frame(s.t, *s.curves);
            vtk_step = s.step;
        }
        // Every n steps (and, below, when stopped early), so that --resume loses nothing.
        if (o.checkpoint_every > 0 && s.step < s.steps && !s.curves->empty() &&
            s.step % o.checkpoint_every == 0) {
            history.save_csv();  // first: a checkpoint's history is never shorter than its run
            write_checkpoint(dir, {given, id, *s.run, overlay.count(), std::nullopt, {}});
            folder.publish();
        }
        if (progress && s.wall_s > 2.0) {
            const double left = s.wall_s * (s.steps - s.step) / s.step;
            fmt::print(stderr, "\rstep {}/{}  t = {:.4g}  segments {}  {:.0f} s left   ", s.step,
                       s.steps, s.t, s.curves->size(), left);
        }
        return !stop_requested;
    };
    const RunResult r = from ? resume(from->state, *law, p.domain, options, observer)
                             : run(initial, *law, p.domain, options, observer);
    // Stopped, between steps or within one: the checkpoint of the last whole step.
    if (r.status == RunStatus::interrupted && o.checkpoint_every > 0 && !r.curves.empty()) {
        history.save_csv();
        write_checkpoint(dir, {given, id, r, overlay.count(), std::nullopt, {}});
        folder.publish();
    }
    if (progress) fmt::print(stderr, "\n");
    // A run that fails says one line, its error; its notes stay in summary.json.
    const bool finished = r.status == RunStatus::ok || r.status == RunStatus::vanished ||
                          r.status == RunStatus::interrupted || r.status == RunStatus::broken;
    warn_broken(r);
    if (finished) note_deeper("curves", options.step.contour.thin_depth, r);
    if (finished && r.domain_doublings > 0) {
        const Box d = doubled_domain(p.domain, r.domain_doublings);
        fmt::print(
            stderr,
            "slc: note: the curves neared the domain's edge at t = {:.6g}; the domain grew "
            "to [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}] and K to {} (summary.json: domain_grown)\n",
            r.domain_grown_at, d.lo.x, d.hi.x, d.lo.y, d.hi.y,
            options.step.contour.depth + r.domain_doublings);
    }

    write_file_atomic(dir / "final.json", interface_json(r.curves, r.t));
    history.save_csv();
    if (o.frames > 0 && ends_frames_where_stopped(r, r.curves.empty(), vtk_step == r.steps_done)) {
        keep_frame(r.t, r.curves);
        vtk_step = r.steps_done;
    }
    if (vtk && vtk_step != r.steps_done) vtk->add(r.t, r.curves);
    draw(dir, p, initial, r, overlay.shown(), overlay.count());
    history.save_plot(p.name);
    nlohmann::json summary = run_summary(p, options, r, *law);
    summary["run_id"] = id;
    if (finished && summary.contains("note"))
        fmt::print(stderr, "slc: note: {}\n", summary["note"].get<std::string>());
    write_file_atomic(dir / "summary.json", summary.dump(2) + "\n");
    if (coarse) {  // the summary is written once without it, in case the extra run is stopped
        summary["error_estimate"] = estimate_json(
            run_name(*coarse), r.status,
            [&] {
                // Ctrl-C stops the extra run too.
                const RunResult c = run(initial, *law, p.domain, *coarse,
                                        [](const StepReport&) { return !stop_requested; });
                return CoarseRun{c.status, c.t, c.cpu_s, c.curves.empty(), final_distance(r, c)};
            },
            "curves");
        write_file_atomic(dir / "summary.json", summary.dump(2) + "\n");
    }
    folder.commit();
    if (!o.quiet) {
        fmt::print("{}: {} at t = {:.6g} after {} steps, e_inf = {}, {:.3g} s cpu{}; wrote {}\n",
                   p.name, to_string(r.status), r.t, r.steps_done, summary["e_inf"].dump(), r.cpu_s,
                   finest_cell_text(summary), folder.target().string());
        if (coarse) print_estimate(summary["error_estimate"]);
    }
    if (r.status == RunStatus::error || r.status == RunStatus::unstable)
        throw NumericalFailure(r.message);
    if (stop_signal != 0) {
        const char* name = stop_signal == SIGINT ? "SIGINT" : "SIGTERM";
        if (r.status != RunStatus::interrupted) {  // the signal came during the final writes
            throw Interrupted(stop_signal, fmt::format("{}: {} came after the last step; the "
                                                       "results in {} are written whole",
                                                       p.name, name, folder.target().string()));
        }
        throw Interrupted(stop_signal,
                          fmt::format("{}: interrupted by {} after step {} at t = "
                                      "{:.6g}; {} holds the run up to there",
                                      p.name, name, r.steps_done, r.t, folder.target().string()));
    }
}

/// The options of `slc run` (all but the action), so that --resume can parse a checkpoint's again.
void add_run_options(CLI::App* cmd, RunCommand* o) {
    add_problem_source_options(*cmd, o->source);
    add_method_options(*cmd, o->method);
    cmd->add_option(
           "--frames", o->frames,
           "Write this many frames (plus the initial one, and where the run stopped if it "
           "stopped early) to DIR/frames/ and draw them overlaid in DIR/frames.svg/.png (at most "
           "64: every n-th and the last). A run of --initial without -N takes a multiple of them, "
           "so that they fall at evenly spaced times; a named problem keeps its N and writes at "
           "most a frame a step")
        ->check(integer_in(0, 100000));
    cmd->add_option("--view", o->view,
                    "For a surface: the direction its pictures look from, AZ,EL in degrees (about "
                    "the z axis from +x, and above the xy plane), or AZ,EL,UP with the up axis x, "
                    "y or z (angles about it, docs/surfaces.md); default the problem's, or 35,25 "
                    "about the up axis the surface's extents suggest");
    cmd->add_flag("--vtk", o->vtk,
                  "Also write the initial interface, the frames and the final one as VTK PolyData "
                  "(DIR/frames/*.vtp) and DIR/frames.pvd, a time series ParaView opens. For "
                  "curves: a surface's frames are written so already");
    cmd->add_flag("--estimate", o->estimate,
                  "After the run, run it again at half resolution (N/2 steps, K - 1, 4 eps; about "
                  "a quarter of the cost or less) and write the distance between the two final "
                  "interfaces (curves or surfaces) to summary.json as \"error_estimate\": an "
                  "estimate of this run's error, for runs without an exact solution "
                  "(conservative: it assumes first order). For several resolutions and observed "
                  "orders, see slc study --initial");
    cmd->add_option("--volume-drift", o->volume_drift,
                    "For a surface under a law that keeps the volume: end the run unstable once "
                    "the volume has drifted from the start's by more than this fraction (default "
                    "0.01). A larger one lets a coarse run finish and report how far it drifted")
        ->check(positive_number());
    cmd->add_flag("--no-guards", o->no_guards,
                  "Take every step whole and go on to the end even when one breaks what the law "
                  "keeps (a part thinner than the contours tears, the area or volume drifts), to "
                  "see what a coarse run gives; the run then ends with status broken, exit "
                  "status 0, and the first break in summary.json's message");
    cmd->add_option("--until-components", o->until_components,
                    "End the run, status ok, once at most this many components are left "
                    "(particles: outer curves; a surface's connected components); --t-end is then "
                    "the latest time")
        ->check(integer_in(1, 100000000));
    cmd->add_flag("--vdb", o->vdb,
                  "For a surface: also write the final surface as DIR/final.vdb, an OpenVDB "
                  "narrow-band level set (FloatGrid 'surface', half-width 3 voxels) holding the "
                  "exact signed distance at the voxel centres, and each frame of --frames as "
                  "DIR/frames/frame_NNNN.vdb; voxel size by --vdb-voxel");
    cmd->add_option("--vdb-voxel", o->vdb_voxel,
                    "The voxel size of DIR/final.vdb (implies --vdb); default half the edge of "
                    "the contour's cells at depth K, and at most 1/128 of the domain's width")
        ->check(positive_number());
    cmd->add_flag("--quiet", o->quiet, "No progress or closing line");
    cmd->add_option("--out", o->out,
                    "Output folder (required, except with --resume): summary.json, final.json, "
                    "final.svg/.png, history.csv/.png, frames; for a surface final.obj, "
                    "final.vtp and final.png instead of final.json and final.svg, "
                    "initial.obj, and final.vdb with --vdb");
    cmd->add_option(
           "--checkpoint-every", o->checkpoint_every,
           "Write DIR/checkpoint.json every n steps, and when stopped by Ctrl-C or SIGTERM")
        ->check(integer_in(1, 100000000));
    cmd->add_option("--resume", o->resume,
                    "Continue the run whose checkpoint is in DIR (its options, its output folder): "
                    "the same final interface, bit for bit, as a run never stopped. Only --threads "
                    "and --quiet may be given with it");
}

/// The folders of DIR where checkpoints keep copies of the files the run read.
const std::vector<std::pair<std::string, std::string>> copied_files = {
    {"--initial", "checkpoint-initial"}, {"--field-file", "checkpoint-field"}};

/// Options that do not change a run's results, left out of its identity.
const std::set<std::string> options_outside_identity = {"--out", "--quiet", "--threads",
                                                        "--checkpoint-every"};

/// The options of the first run, to keep in checkpoints. With --initial (and --field-file), a
/// copy of the file goes to DIR/checkpoint-initial/ (DIR/checkpoint-field/) in the working
/// folder `work` and the checkpoint names the copy, which --resume reads.
std::vector<GivenOption> options_to_keep(const CLI::App& cmd, const RunCommand& o,
                                         const std::filesystem::path& work) {
    std::vector<GivenOption> given = given_options(cmd, {"--out", "--quiet", "--threads"});
    if (o.checkpoint_every == 0 || o.source.initial.empty()) return given;
    for (auto& [option, values] : given) {
        for (const auto& [copied, folder] : copied_files) {
            if (option != copied || values.size() != 1) continue;
            const std::filesystem::path name = std::filesystem::path(values[0]).filename();
            write_file_atomic(work / folder / name, read_text_file(values[0]));
            values = {name.string()};
        }
    }
    return given;
}

void surface_command(const RunCommand& o, const std::vector<GivenOption>& given,
                     const std::string& id, const Checkpoint* from, OutputFolder& folder);

/// --resume DIR: the checkpoint's options parsed again, with DIR as the output folder.
void resume_command(const CLI::App& cmd, const RunCommand& o) {
    const StopSignals signals;
    const std::vector<GivenOption> extra = given_options(cmd, {"--resume", "--threads", "--quiet"});
    if (!extra.empty()) {
        throw InvalidInput(fmt::format(
            "--resume takes the run's options from its checkpoint; {} cannot be given with it",
            extra.front().first));
    }
    const std::filesystem::path dir(o.resume);
    read_checkpoint(dir);  // a folder without a checkpoint is refused before it is locked
    OutputFolder out(dir, true);
    const Checkpoint c = read_checkpoint(dir);  // again: another run may have replaced it
    std::vector<std::string> args = as_arguments(c.options);
    for (std::string& arg : args) {
        for (const auto& [option, folder] : copied_files) {
            const std::string prefix = option + "=";
            if (arg.starts_with(prefix))
                arg = prefix + (dir / folder / arg.substr(prefix.size())).string();
        }
    }
    args.push_back("--out=" + o.resume);
    if (o.quiet) args.push_back("--quiet");
    if (o.method.threads != 0) args.push_back(fmt::format("--threads={}", o.method.threads));
    CLI::App again;
    RunCommand resumed;
    add_run_options(&again, &resumed);
    std::reverse(args.begin(), args.end());  // CLI11 takes a vector of arguments last first
    again.parse(args);
    if (c.surface) return surface_command(resumed, c.options, c.run_id, &c, out);
    run_command(resumed, c.options, c.run_id, &c, out);
}

/// slc run on a surface: the options that apply to surfaces, the others refused by name; from
/// the checkpoint `from` when given. The caller installs the StopSignals.
void surface_command(const RunCommand& o, const std::vector<GivenOption>& given,
                     const std::string& id, const Checkpoint* from, OutputFolder& folder) {
    // The settings of curves among the method options are refused by apply_overrides.
    const std::vector<std::pair<bool, const char*>> curve_only = {
        {o.vtk, "--vtk"}, {!o.method.geometry.empty(), "--geometry"}};
    for (const auto& [given_option, name] : curve_only)
        if (given_option) throw InvalidInput(fmt::format("{} is for curves, not surfaces", name));
    apply_threads(o.method.threads);
    run_surface({.problem = o.source.problem,
                 .initial = o.source.initial,
                 .velocity = o.source.velocity,
                 .speed = o.source.speed,
                 .field = o.source.field,
                 .field_file = o.source.field_file,
                 .field_zero_outside = o.source.field_outside == "zero",
                 .params = o.source.params,
                 .t_end = o.source.t_end,
                 .domain = o.source.domain,
                 .settings = run_settings(o),
                 .frames = o.frames,
                 .estimate = o.estimate,
                 .view = o.view,
                 .vdb = o.vdb || o.vdb_voxel.has_value(),
                 .vdb_voxel = o.vdb_voxel,
                 .quiet = o.quiet,
                 .checkpoint_every = o.checkpoint_every,
                 .given = given,
                 .run_id = id,
                 .from = from,
                 .stop_signal = &stop_signal},
                folder);
}

}  // namespace

void add_run_command(CLI::App& app) {
    const auto [cmd, o] = add_command<RunCommand>(
        app, "run",
        "Moves an interface under a velocity law: a named problem (--problem), or your curves "
        "or surface (--initial)");
    add_run_options(cmd, o.get());
    cmd->callback([o, cmd] {
        if (!o->resume.empty()) return resume_command(*cmd, *o);
        if (o->source.problem.empty() && o->source.initial.empty())
            throw InvalidInput("give --problem NAME or --initial FILE");
        if (o->out.empty()) throw InvalidInput("--out DIR is required");
        const bool surface = is_surface_run(o->source.problem, o->source.initial);
        if (!surface && o->view) throw InvalidInput("--view is for surfaces, not curves");
        if (!surface && o->volume_drift)
            throw InvalidInput("--volume-drift is for surfaces, not curves");
        if (!surface && o->source.field_file && is_vdb_file(*o->source.field_file))
            throw InvalidInput("--field-file: an OpenVDB field (.vdb) moves surfaces, not curves");
        if (!surface && (o->vdb || o->vdb_voxel))
            throw InvalidInput(
                fmt::format("{} is for surfaces, not curves", o->vdb ? "--vdb" : "--vdb-voxel"));
        const StopSignals signals;
        const std::vector<GivenOption> all = given_options(*cmd, {});
        const std::string id =
            run_identity(all, options_outside_identity, {"--initial", "--field-file"});
        OutputFolder folder(o->out, false);
        if (surface)
            return surface_command(*o, options_to_keep(*cmd, *o, folder.path()), id, nullptr,
                                   folder);
        run_command(*o, options_to_keep(*cmd, *o, folder.path()), id, nullptr, folder);
    });
}

}  // namespace slc::cli
