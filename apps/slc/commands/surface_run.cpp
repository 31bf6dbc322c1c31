// slc run on a surface: a named surface problem or the user's surface under a law of surfaces;
// writes summary.json, final.obj/.vtp/.png, history.csv/.png and frames.
#include "commands/surface_run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string_view>

#include "commands/commands.hpp"
#include "commands/output_folder.hpp"
#include "commands/run_options.hpp"
#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/stop.hpp"
#include "slc/evolve/surface_problems.hpp"
#include "slc/evolve/surface_study.hpp"
#include "slc/io/interface_json.hpp"
#include "slc/io/plot.hpp"
#include "slc/io/summary.hpp"
#include "slc/io/surface_files.hpp"
#include "slc/io/surface_picture.hpp"
#include "slc/io/vdb.hpp"
#include "slc/io/vtk.hpp"
#include "slc/velocity/expression.hpp"
#include "slc/velocity/zero_outside.hpp"

namespace slc::cli {
namespace {

/// One line of history.csv, and what the history plot shows.
struct HistoryRow {
    int step = 0;
    double t = 0.0, volume = 0.0, area = 0.0;
    std::size_t triangles = 0, components = 0;
};

std::string history_line(const HistoryRow& h) {
    return fmt::format("{},{:.17g},{:.17g},{:.17g},{},{}\n", h.step, h.t, h.volume, h.area,
                       h.triangles, h.components);
}

HistoryRow row_of(int step, double t, const Surface& s) {
    return {step, t, volume(s), area(s), s.size(), s.empty() ? 0 : component_count(s)};
}

/// The first steps_done + 1 lines of a history.csv an earlier run wrote (after its header),
/// read back for a resumed run; InvalidInput naming the file when it is shorter, malformed or
/// not at time t after steps_done steps.
std::vector<HistoryRow> read_history(const std::filesystem::path& csv, int steps_done, double t) {
    const std::string text = read_text_file(csv);
    std::vector<HistoryRow> rows;
    std::size_t at = text.find('\n');  // past the header
    while (at != std::string::npos && rows.size() < static_cast<std::size_t>(steps_done) + 1) {
        const std::size_t end = text.find('\n', at + 1);
        if (end == std::string::npos) break;
        const std::string line = text.substr(at + 1, end - at - 1);
        HistoryRow h;
        if (std::sscanf(line.c_str(), "%d,%lf,%lf,%lf,%zu,%zu", &h.step, &h.t, &h.volume, &h.area,
                        &h.triangles, &h.components) != 6 ||
            h.step != static_cast<int>(rows.size())) {
            throw InvalidInput(fmt::format("{}: line {} is not the history of step {}",
                                           csv.string(), rows.size() + 2, rows.size()));
        }
        rows.push_back(h);
        at = end;
    }
    if (rows.size() != static_cast<std::size_t>(steps_done) + 1 || rows.back().t != t) {
        throw InvalidInput(
            fmt::format("{}: does not hold the run's {} steps up to t = {} of its checkpoint",
                        csv.string(), steps_done, t));
    }
    return rows;
}

void draw_history(const std::vector<HistoryRow>& rows, const std::string& title,
                  const std::filesystem::path& path) {
    LinePlot plot{.title = title, .x_name = "t", .panels = {}};
    PlotSeries v, a;
    for (const HistoryRow& h : rows) {
        v.x.push_back(h.t);
        v.y.push_back(h.volume);
        a.x.push_back(h.t);
        a.y.push_back(h.area);
    }
    plot.panels.push_back({"volume", {v}});
    plot.panels.push_back({"area", {a}});
    save_plot(plot, path);
}

}  // namespace

double default_vdb_voxel(const Box3& domain, int depth) {
    return domain.width() / std::max(128.0, std::ldexp(1.0, depth + 1));
}

bool is_surface_run(const std::string& problem, const std::string& initial) {
    return (!problem.empty() && is_surface_problem(problem)) ||
           (!initial.empty() && is_surface_file(initial));
}

SurfaceRunSetup resolve_surface_run(const SurfaceRunRequest& r) {
    const VelocityParams params = parse_params(r.params);
    SurfaceProblem p;
    if (!r.problem.empty()) {
        p = make_surface_problem(r.problem, params);
        if (r.t_end) p.t_end = *r.t_end;
        if (r.domain.half_width || r.domain.box) {
            p.domain = resolve_domain3(r.domain, bounding_box(p.initial));
            for (const Vec3& v : p.initial.vertices) {
                if (!p.domain.contains(v))
                    throw InvalidInput("the problem's surface leaves the domain given");
            }
        }
    } else {
        one_velocity_law({{"--velocity", !r.velocity.empty()},
                          {"--speed", r.speed.has_value()},
                          {"--field", r.field.has_value()},
                          {"--field-file", r.field_file.has_value()}},
                         "--initial with a surface needs --velocity NAME, --speed, --field or "
                         "--field-file");
        if (!r.t_end) throw InvalidInput("--initial needs --t-end");
        LoadedSurface in = load_surface(r.initial, r.domain);
        p.name = std::filesystem::path(r.initial).stem().string();
        p.initial = std::move(in.surface);
        p.domain = in.domain;
        if (r.field_file && !is_vdb_file(*r.field_file)) {
            throw InvalidInput(fmt::format(
                "--field-file for a surface takes an OpenVDB vector grid (.vdb), got '{}'",
                *r.field_file));
        }
        p.law = r.speed   ? surface_speed_expression_law(*r.speed, params)
                : r.field ? surface_field_expression_law(*r.field, params)
                : r.field_file && r.field_zero_outside
                    ? zero_outside_extent(vdb_field_law(*r.field_file))
                : r.field_file ? vdb_field_law(*r.field_file)
                               : make_surface_velocity(r.velocity, params);
        p.t_end = *r.t_end;
    }
    SurfaceRunOptions options =
        surface_run_options(p, !r.problem.empty(), 0.0, r.settings, SettingNames::tool);
    return {std::move(p), std::move(options)};
}

void run_surface(const SurfaceRunRequest& r, OutputFolder& folder) {
    SurfaceRunSetup setup = resolve_surface_run(r);
    SurfaceProblem& p = setup.problem;
    SurfaceRunOptions& options = setup.options;  // surface_as_read may deepen its thin cells
    const int thin_asked = options.step.contour.thin_depth;
    const SurfaceContourOptions& c = options.step.contour;
    try {
        // A named problem's surface at the run's own K, P, ε and η when they are given: a run at
        // K = 7 starts from the contour at K = 7, not from the problem's coarser one.
        if (!r.problem.empty() && sets_contour(r.settings)) p.initial = initial_surface(p, c);
        // A user's surface as the steps read it (surface_as_read), contoured at the run's K and
        // ε.
        if (r.problem.empty()) p.initial = surface_as_read(p.initial, p.domain, options);
    } catch (const StopRequested&) {
        const int signal = r.stop_signal != nullptr ? r.stop_signal->load() : SIGINT;
        throw Interrupted(signal,
                          fmt::format("{}: interrupted by {} while contouring the initial surface, "
                                      "before the first step; nothing was written",
                                      p.name, signal == SIGTERM ? "SIGTERM" : "SIGINT"));
    }
    SurfaceView view;
    view.azimuth = p.azimuth;
    view.elevation = p.elevation;
    if (r.view) {
        // AZ,EL and optionally the up axis: "30,20" or "30,20,y".
        std::string angles_text = *r.view;
        const std::size_t last = angles_text.rfind(',');
        if (last != std::string::npos && last + 2 == angles_text.size() &&
            std::string_view("xyz").find(angles_text.back()) != std::string_view::npos) {
            const char axis = angles_text.back();
            view.up = axis == 'x' ? UpAxis::x : axis == 'y' ? UpAxis::y : UpAxis::z;
            angles_text.resize(last);
        }
        const auto angles = comma_numbers(angles_text);
        if (!angles || angles->size() != 2 || !std::isfinite((*angles)[0]) ||
            !std::isfinite((*angles)[1])) {
            throw InvalidInput(fmt::format(
                "--view must be two finite numbers AZ,EL in degrees, got '{}'", *r.view));
        }
        view.azimuth = (*angles)[0];
        view.elevation = (*angles)[1];
    } else if (r.problem.empty()) {
        view.up = up_axis(bounding_box(p.initial));  // a y-up scan stands up
    }
    auto titled = [&view](std::string title) {
        SurfaceView v = view;
        v.title = std::move(title);
        return v;
    };

    // --estimate's run at half resolution, resolved first so that one it cannot have (N or K
    // of 1) is an input error before anything runs.
    if (r.estimate) require_half_resolution(options.steps, options.step.contour.depth);
    const std::optional<SurfaceRunOptions> coarse =
        r.estimate ? std::optional(surface_resolution_options(options, -1)) : std::nullopt;

    // final.vdb's voxel, refused before the run when too fine for the domain.
    const double vdb_voxel =
        r.vdb_voxel ? *r.vdb_voxel : default_vdb_voxel(p.domain, options.step.contour.depth);
    if (r.vdb && !(p.domain.width() / vdb_voxel <= max_vdb_voxels_per_side)) {
        throw InvalidInput(fmt::format(
            "--vdb-voxel {} is too fine for the domain, {} wide: more than {} voxels a side",
            vdb_voxel, p.domain.width(), max_vdb_voxels_per_side));
    }

    const Checkpoint* from = r.from;
    if (from) check_surface_checkpoint(*from, p.domain, options, folder.target());
    const std::filesystem::path dir = folder.path();
    std::vector<HistoryRow> history;
    if (from) {
        history = read_history(folder.target() / "history.csv", from->surface->steps_done,
                               from->surface->t);
    } else {
        history.push_back(row_of(0, options.t_start, p.initial));
        write_file_atomic(dir / "initial.obj", obj_text(p.initial));
    }
    std::string history_text = "step,t,volume,area,triangles,components\n";
    for (const HistoryRow& h : history) history_text += history_line(h);

    // Frames 0..F at evenly spaced steps, as .vtp (with a .pvd collection) and shaded PNGs, and
    // with --vdb as OpenVDB level sets.
    const int frames = std::min(r.frames, options.steps);
    std::optional<VtkSeries> series;
    auto frame_png = [&](int i) { return dir / "frames" / fmt::format("frame_{:04d}.png", i); };
    int frames_written = 0;
    std::vector<double> frame_times;
    auto write_frame = [&](double t, const Surface& s) {
        series->add(t, s);
        frame_times.push_back(t);
        if (!s.empty()) {
            save_surface_picture(s, frame_png(frames_written),
                                 titled(fmt::format("{}: t = {:.4g}", p.name, t)));
            if (r.vdb) {
                write_vdb_level_set(
                    dir / "frames" / fmt::format("frame_{:04d}.vdb", frames_written), s,
                    {.voxel = vdb_voxel});
            }
        }
        ++frames_written;
    };
    if (frames > 0) {
        series.emplace(dir / "frames.pvd");
        if (from) {  // the frames written before the checkpoint, kept in the folder
            series->keep(from->frame_times);
            frame_times = from->frame_times;
            frames_written = from->frames_kept;
        } else {
            write_frame(options.t_start, p.initial);
        }
    }
    const SurfaceObserver observer = [&](const SurfaceStepReport& report) {
        history.push_back(row_of(report.step, report.t, *report.surface));
        history_text += history_line(history.back());
        if (frames > 0) {
            // Step n ends frame j when n = ⌈j N / F⌉.
            const long long j = static_cast<long long>(report.step) * frames / report.steps;
            const long long first_step_of_j =
                (j * report.steps + frames - 1) / frames;  // ⌈j N / F⌉
            if (j >= frames_written && first_step_of_j == report.step)
                write_frame(report.t, *report.surface);
        }
        // Every n steps (and, below, when stopped early), so that --resume loses nothing.
        if (r.checkpoint_every > 0 && report.step < report.steps && !report.surface->empty() &&
            report.step % r.checkpoint_every == 0) {
            write_file_atomic(dir / "history.csv", history_text);  // never shorter than the run
            write_checkpoint(dir,
                             {r.given, r.run_id, {}, frames_written, *report.run, frame_times});
            folder.publish();
        }
        if (!r.quiet) {
            fmt::print("step {}/{}  t = {:.6g}  {} triangles  volume {:.6g}\n", report.step,
                       report.steps, report.t, report.surface->size(), volume(*report.surface));
            std::fflush(stdout);
        }
        return r.stop_signal == nullptr || *r.stop_signal == 0;
    };
    const SurfaceRunResult result =
        from ? resume(*from->surface, *p.law, p.domain, options, observer)
             : run(p.initial, *p.law, p.domain, options, observer);
    // Stopped, between steps or within one: the checkpoint of the last whole step.
    if (result.status == RunStatus::interrupted && r.checkpoint_every > 0 &&
        !result.surface.empty()) {
        write_file_atomic(dir / "history.csv", history_text);
        write_checkpoint(dir, {r.given, r.run_id, {}, frames_written, result, frame_times});
        folder.publish();
    }

    if (frames > 0 &&
        ends_frames_where_stopped(result, result.surface.empty(),
                                  !frame_times.empty() && frame_times.back() == result.t))
        write_frame(result.t, result.surface);
    const Surface& s = result.surface;
    nlohmann::json summary = surface_run_summary(p, p.initial, options, result);
    // A run that fails says one line, its error; its notes stay in summary.json.
    const bool finished = result.status == RunStatus::ok ||
                          result.status == RunStatus::interrupted ||
                          result.status == RunStatus::broken;
    warn_broken(result);
    if (finished && summary.contains("note"))
        fmt::print(stderr, "slc: note: {}\n", summary["note"].get<std::string>());
    if (finished) note_deeper("surface", thin_asked, result);
    if (finished && result.domain_doublings > 0) {
        const Box3 d = doubled_domain(p.domain, result.domain_doublings);
        fmt::print(stderr,
                   "slc: note: the surface neared the domain's edge at t = {:.6g}; the domain grew "
                   "to [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}] and K to {} "
                   "(summary.json: domain_grown)\n",
                   result.domain_grown_at, d.lo.x, d.hi.x, d.lo.y, d.hi.y, d.lo.z, d.hi.z,
                   options.step.contour.depth + result.domain_doublings);
    }
    summary["run_id"] = r.run_id;
    const double e = summary["e_inf"].is_null() ? std::nan("") : summary["e_inf"].get<double>();
    write_file_atomic(dir / "history.csv", history_text);
    draw_history(history, fmt::format("{}: volume and area", p.name), dir / "history.png");
    write_file_atomic(dir / "final.obj", obj_text(s));
    write_file_atomic(dir / "final.vtp", vtp_text(s, result.t));
    if (r.vdb && !s.empty()) {
        write_vdb_level_set(dir / "final.vdb", s, {.voxel = vdb_voxel});
        summary["vdb_voxel"] = vdb_voxel;
    }
    const std::string title = fmt::format(
        "{}: t = {:.4g} ({}), {} triangles{}", p.name, result.t, to_string(result.status), s.size(),
        std::isfinite(e) ? fmt::format(", e_inf {:.2e}", e) : std::string());
    if (!s.empty()) {
        // Coloured by how far each point moved from the start, outward positive.
        const SurfaceColoring moved{vertex_distances(s, p.initial),
                                    "distance from the initial surface (+ outside it)"};
        save_surface_picture(s, moved, dir / "final.png", titled(title));
        // And from along the axes, where a part the first view hides shows.
        SurfaceView four = titled(title);
        four.width = four.height = 500;
        save_surface_views(std::span<const Surface>(&s, 1), dir / "views.png", four);
    } else {
        save_surface_picture(
            p.initial, dir / "final.png",
            titled(fmt::format("{}: everything vanished by t = {:.4g}", p.name, result.t)));
    }
    write_file_atomic(dir / "summary.json", summary.dump(2) + "\n");
    if (coarse) {
        summary["error_estimate"] = estimate_json(
            run_name(*coarse), result.status,
            [&] {
                // The run again from the same surface; a stop signal stops it too.
                const SurfaceRunResult other =
                    run(p.initial, *p.law, p.domain, *coarse, [&r](const SurfaceStepReport&) {
                        return r.stop_signal == nullptr || *r.stop_signal == 0;
                    });
                return CoarseRun{other.status, other.t, other.cpu_s, other.surface.empty(),
                                 final_distance(result, other)};
            },
            "surface");
        write_file_atomic(dir / "summary.json", summary.dump(2) + "\n");
    }
    folder.commit();
    if (result.status == RunStatus::error || result.status == RunStatus::unstable)
        throw NumericalFailure(result.message);
    if (r.stop_signal != nullptr && *r.stop_signal != 0) {
        const int signal = *r.stop_signal;
        const char* name = signal == SIGINT ? "SIGINT" : "SIGTERM";
        if (result.status != RunStatus::interrupted) {  // the signal came during the writes
            throw Interrupted(signal, fmt::format("{}: {} came after the last step; the results "
                                                  "in {} are written whole",
                                                  p.name, name, folder.target().string()));
        }
        throw Interrupted(signal, fmt::format("{}: interrupted by {} after step {} at t = {:.6g}; "
                                              "{} holds the run up to there",
                                              p.name, name, result.steps_done, result.t,
                                              folder.target().string()));
    }
    if (!r.quiet) {
        fmt::print(
            "{} steps to t = {:.6g}: {}, {} triangles, volume change {:.3g}{}, {:.3g} s{}; "
            "wrote {}\n",
            result.steps_done, result.t, to_string(result.status), s.size(),
            summary["volume_change"].get<double>(),
            std::isfinite(e) ? fmt::format(", e_inf {:.3g}", e) : std::string(), result.cpu_s,
            finest_cell_text(summary), (folder.target() / "summary.json").string());
        if (coarse) print_estimate(summary["error_estimate"]);
    }
}

}  // namespace slc::cli
