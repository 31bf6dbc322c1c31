// Checkpoints of slc run: writing and reading DIR/checkpoint.json.
#include "commands/checkpoint.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string_view>

#include "slc/core/error.hpp"
#include "slc/geometry/validate.hpp"
#include "slc/geometry/validate_surface.hpp"
#include "slc/io/interface_json.hpp"

namespace slc {

// What a checkpoint keeps of each dimension's run besides RunTotals (put_totals) and the
// interface, under the fields' own names; a field missing from the file keeps its default.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(RunLeast, value, t)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(RunResult, vertices_produced, area_corrected,
                                                start_area, area_lag, area_law_change,
                                                rigid_segments, least_length)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(SurfaceRunResult, volume_initial, volume_corrected,
                                                unconverged_steps, largest_residual, least_area)

}  // namespace slc

namespace slc::cli {
namespace {

using Json = nlohmann::json;

constexpr const char* format_name = "slc run checkpoint 2";

/// Each curve as one flat array x0, y0, x1, y1, ...; nlohmann-json writes every double in its
/// shortest round-trip form, so the checkpoint reads back bit for bit.
Json curves_json(const Interface& curves) {
    Json out = Json::array();
    for (std::size_t c = 0; c < curves.curve_count(); ++c) {
        Json flat = Json::array();
        for (const Vec2 p : curves.curve(c)) {
            flat.push_back(p.x);
            flat.push_back(p.y);
        }
        out.push_back(std::move(flat));
    }
    return out;
}

/// A surface as flat arrays: "vertices" x0, y0, z0, x1, ... and "triangles" a0, b0, c0, ...
void put_surface(Json& json, const Surface& s) {
    Json xyz = Json::array(), abc = Json::array();
    for (const Vec3& v : s.vertices) {
        xyz.push_back(v.x);
        xyz.push_back(v.y);
        xyz.push_back(v.z);
    }
    for (const TriangleIndices& t : s.triangles)
        for (const std::uint32_t i : t) abc.push_back(i);
    json["vertices"] = std::move(xyz);
    json["triangles"] = std::move(abc);
}

Surface surface_from(const Json& json) {
    const auto xyz = json.at("vertices").get<std::vector<double>>();
    const auto abc = json.at("triangles").get<std::vector<std::uint32_t>>();
    if (xyz.size() % 3 != 0 || abc.size() % 3 != 0)
        throw InvalidInput("vertices or triangles are not in threes");
    Surface s;
    for (std::size_t i = 0; i < xyz.size(); i += 3)
        s.vertices.push_back({xyz[i], xyz[i + 1], xyz[i + 2]});
    for (std::size_t i = 0; i < abc.size(); i += 3)
        s.triangles.push_back({abc[i], abc[i + 1], abc[i + 2]});
    return s;
}

/// Refuses results in dir that belong to another run or are past the checkpoint's step.
void check_results_beside(const std::string& run_id, int steps_done,
                          const std::filesystem::path& dir) {
    const std::filesystem::path summary_path = dir / "summary.json";
    if (!std::filesystem::exists(summary_path)) return;
    Json summary;
    try {
        summary = Json::parse(read_text_file(summary_path));
    } catch (const Json::exception&) {
        return;  // a summary that is not JSON is not results to protect
    }
    if (summary.value("run_id", std::string()) != run_id) {
        throw InvalidInput(fmt::format(
            "{}: the results in the folder belong to another run (run_id {}, the checkpoint's "
            "{}); resume refused",
            summary_path.string(), summary.value("run_id", std::string("none")), run_id));
    }
    const int done = summary.value("steps_done", 0);
    if (done > steps_done) {
        throw InvalidInput(
            fmt::format("{}: the results are of step {}, after the checkpoint's step {}; remove "
                        "summary.json to run from the checkpoint again",
                        summary_path.string(), done, steps_done));
    }
}

Interface curves_from(const Json& json) {
    std::vector<std::vector<Vec2>> curves;
    for (const Json& flat : json) {
        const auto xy = flat.get<std::vector<double>>();
        if (xy.size() % 2 != 0) throw InvalidInput("a curve has an odd number of coordinates");
        std::vector<Vec2>& curve = curves.emplace_back();
        for (std::size_t i = 0; i < xy.size(); i += 2) curve.push_back({xy[i], xy[i + 1]});
        for (const Vec2 p : curve)
            if (!is_finite(p)) throw InvalidInput("a coordinate is not finite");
    }
    return Interface(curves);
}

/// The fields of a run's state both dimensions share.
void put_totals(Json& json, const RunTotals& s) {
    json["steps_done"] = s.steps_done;
    json["t"] = s.t;
    json["g_evals"] = s.g_evals;
    json["wall_s"] = s.wall_s;
    json["cpu_s"] = s.cpu_s;
    json["split_steps"] = s.split_steps;
    json["most_substeps"] = s.most_substeps;
    json["domain_doublings"] = s.domain_doublings;
    if (s.domain_doublings > 0) json["domain_grown_at"] = s.domain_grown_at;
    if (s.finest_cell > 0.0)
        json["finest_cell"] = {{"width", s.finest_cell}, {"at_t", s.finest_t}, {"at", s.finest_at}};
    if (!std::isnan(s.thin_budget_at)) json["thin_budget_at"] = s.thin_budget_at;
    json["thin_depth"] = s.thin_depth;
    if (!std::isnan(s.deeper_at))
        json["thin_deeper"] = {{"at_t", s.deeper_at},
                               {"why", s.deeper_why},
                               {"depth", s.deepest_thin_depth},
                               {"steps", s.deeper_steps}};
    if (!std::isnan(s.shallower_at))
        json["thin_shallower"] = {{"at_t", s.shallower_at},
                                  {"why", s.shallower_why},
                                  {"depth", s.shallowest_thin_depth},
                                  {"substeps", s.shallower_substeps}};
    if (const ThinSplit& t = s.thin_split; !std::isnan(t.at)) {
        json["thin_split"] = {
            {"at_t", t.at}, {"thickness", t.thickness}, {"cell", t.cell}, {"near", t.near}};
    }
    if (!s.broken.empty()) json["broken"] = s.broken;
}

/// Reads what put_totals() wrote; the run it describes was interrupted.
void get_totals(const Json& json, RunTotals& s) {
    s.steps_done = json.at("steps_done").get<int>();
    s.t = json.at("t").get<double>();
    s.g_evals = json.at("g_evals").get<std::size_t>();
    s.wall_s = json.at("wall_s").get<double>();
    s.cpu_s = json.at("cpu_s").get<double>();
    s.split_steps = json.value("split_steps", 0);
    s.most_substeps = json.value("most_substeps", 1);
    s.domain_doublings = json.value("domain_doublings", 0);
    if (s.domain_doublings > 0) s.domain_grown_at = json.at("domain_grown_at").get<double>();
    if (json.contains("finest_cell")) {
        const Json& f = json.at("finest_cell");
        s.finest_cell = f.at("width").get<double>();
        s.finest_t = f.at("at_t").get<double>();
        s.finest_at = f.at("at").get<std::vector<double>>();
    }
    if (json.contains("thin_budget_at")) s.thin_budget_at = json.at("thin_budget_at").get<double>();
    s.status = RunStatus::interrupted;
    s.thin_depth = json.value("thin_depth", json.value("start_thin_depth", -1));
    if (json.contains("thin_split")) {
        const Json& t = json.at("thin_split");
        s.thin_split = {t.at("at_t").get<double>(), t.at("thickness").get<double>(),
                        t.at("cell").get<double>(), t.at("near").get<std::vector<double>>()};
    }
    if (json.contains("thin_deeper")) {
        s.deeper_at = json.at("thin_deeper").at("at_t").get<double>();
        s.deeper_why = json.at("thin_deeper").at("why").get<std::string>();
        s.deepest_thin_depth = json.at("thin_deeper").value("depth", s.thin_depth);
        s.deeper_steps = json.at("thin_deeper").value("steps", 1);
    }
    if (json.contains("thin_shallower")) {
        const Json& d = json.at("thin_shallower");
        s.shallower_at = d.at("at_t").get<double>();
        s.shallower_why = d.at("why").get<std::string>();
        s.shallowest_thin_depth = d.at("depth").get<int>();
        s.shallower_substeps = d.at("substeps").get<int>();
    }
    s.broken = json.value("broken", std::string());
}

}  // namespace

std::filesystem::path checkpoint_path(const std::filesystem::path& dir) {
    return dir / "checkpoint.json";
}

void write_checkpoint(const std::filesystem::path& dir, const Checkpoint& c) {
    Json options = Json::array();
    for (const auto& [name, values] : c.options) options.push_back({name, values});
    Json json;
    json["format"] = format_name;
    json["options"] = options;
    json["run_id"] = c.run_id;
    if (c.surface) {
        json["dimension"] = 3;
        put_totals(json, *c.surface);
        json.update(Json(*c.surface));
        json["frame_times"] = c.frame_times;
        put_surface(json, c.surface->surface);
    } else {
        put_totals(json, c.state);
        json.update(Json(c.state));
        json["curves"] = curves_json(c.state.curves);
    }
    json["frames_kept"] = c.frames_kept;
    write_file_atomic(checkpoint_path(dir), json.dump() + "\n");
}

Checkpoint read_checkpoint(const std::filesystem::path& dir) {
    const std::filesystem::path path = checkpoint_path(dir);
    const std::string text = read_text_file(path);
    try {
        const Json json = Json::parse(text);
        if (json.at("format") != format_name) throw InvalidInput("unknown format");
        Checkpoint c;
        for (const Json& option : json.at("options")) {
            c.options.emplace_back(option.at(0).get<std::string>(),
                                   option.at(1).get<std::vector<std::string>>());
        }
        c.run_id = json.at("run_id").get<std::string>();
        if (json.value("dimension", 2) == 3) {
            SurfaceRunResult& s = c.surface.emplace();
            get_totals(json, s);
            json.get_to(s);
            c.frame_times = json.at("frame_times").get<std::vector<double>>();
            s.surface = surface_from(json);
        } else {
            get_totals(json, c.state);
            json.get_to(c.state);
            c.state.curves = curves_from(json.at("curves"));
        }
        c.frames_kept = json.at("frames_kept").get<int>();
        return c;
    } catch (const std::exception& e) {
        // nlohmann-json's messages are one line: "[json.exception.type_error.302] ...".
        throw InvalidInput(
            fmt::format("{}: not a checkpoint of slc run ({})", path.string(), e.what()));
    }
}

void check_checkpoint(const Checkpoint& c, const Box& domain, const RunOptions& options,
                      const std::filesystem::path& dir) {
    const std::string path = checkpoint_path(dir).string();
    auto fail = [&](const std::string& why) {
        return InvalidInput(fmt::format("{}: not a checkpoint of this run ({})", path, why));
    };
    const RunResult& s = c.state;
    if (s.steps_done < 0 || s.steps_done >= options.steps) {
        throw fail(fmt::format("steps_done {} is not below the run's {} steps", s.steps_done,
                               options.steps));
    }
    if (!std::isfinite(s.t)) throw fail("t is not finite");
    if (c.frames_kept < 0) throw fail(fmt::format("frames_kept is {}", c.frames_kept));
    if (s.domain_doublings < 0 || s.domain_doublings > options.max_domain_doublings) {
        throw fail(fmt::format("domain_doublings {} is not from 0 to {}", s.domain_doublings,
                               options.max_domain_doublings));
    }
    // The curves as an interface file's: a checkpoint edited by hand must not reach the tree.
    std::vector<std::vector<Vec2>> raw;
    for (std::size_t i = 0; i < s.curves.curve_count(); ++i) {
        const auto curve = s.curves.curve(i);
        raw.emplace_back(curve.begin(), curve.end());
    }
    try {
        const PreparedInterface prepared =
            prepare_interface(raw, doubled_domain(domain, s.domain_doublings));
        if (!prepared.notes.empty()) throw InvalidInput(prepared.notes.front());
    } catch (const InvalidInput& e) {
        throw InvalidInput(fmt::format("{}: {}", path, e.what()));
    }
    // The results beside it: of this run, and not past the checkpoint.
    check_results_beside(c.run_id, s.steps_done, dir);
}

void check_surface_checkpoint(const Checkpoint& c, const Box3& domain,
                              const SurfaceRunOptions& options, const std::filesystem::path& dir) {
    const std::string path = checkpoint_path(dir).string();
    auto fail = [&](const std::string& why) {
        return InvalidInput(fmt::format("{}: not a checkpoint of this run ({})", path, why));
    };
    if (!c.surface) throw fail("it holds curves, not a surface");
    const SurfaceRunResult& s = *c.surface;
    if (s.steps_done < 0 || s.steps_done >= options.steps) {
        throw fail(fmt::format("steps_done {} is not below the run's {} steps", s.steps_done,
                               options.steps));
    }
    if (!std::isfinite(s.t)) throw fail("t is not finite");
    if (c.frames_kept < 0 || static_cast<std::size_t>(c.frames_kept) != c.frame_times.size())
        throw fail(fmt::format("frames_kept is {}", c.frames_kept));
    if (!(s.volume_initial > 0.0) || !std::isfinite(s.volume_initial))
        throw fail("volume_initial is not positive");
    if (s.domain_doublings < 0 || s.domain_doublings > options.max_domain_doublings) {
        throw fail(fmt::format("domain_doublings {} is not from 0 to {}", s.domain_doublings,
                               options.max_domain_doublings));
    }
    // The surface as a surface file's: a checkpoint edited by hand must not reach the tree.
    try {
        const PreparedSurface prepared = prepare_surface(s.surface);
        if (!prepared.notes.empty()) throw InvalidInput(prepared.notes.front());
        const Box3 grown = doubled_domain(domain, s.domain_doublings);
        for (const Vec3& v : s.surface.vertices)
            if (!grown.contains(v)) throw InvalidInput("a vertex lies outside the domain");
    } catch (const InvalidInput& e) {
        throw InvalidInput(fmt::format("{}: {}", path, e.what()));
    }
    check_results_beside(c.run_id, s.steps_done, dir);
}

std::string run_identity(const std::vector<GivenOption>& options, const std::set<std::string>& skip,
                         const std::set<std::string>& files) {
    // FNV-1a, 64 bits: stable across builds and machines, unlike std::hash.
    std::uint64_t h = 14695981039346656037ull;
    auto add = [&h](std::string_view bytes) {
        for (const char b : bytes) {
            h ^= static_cast<unsigned char>(b);
            h *= 1099511628211ull;
        }
        h ^= 0xff;  // a separator, so that "ab","c" and "a","bc" differ
        h *= 1099511628211ull;
    };
    for (const auto& [name, values] : options) {
        if (skip.contains(name)) continue;
        add(name);
        for (const std::string& value : values) {
            add(value);
            if (files.contains(name)) add(read_text_file(value));
        }
    }
    return fmt::format("{:016x}", h);
}

std::vector<GivenOption> given_options(const CLI::App& cmd, const std::set<std::string>& skip) {
    std::vector<GivenOption> out;
    for (const CLI::Option* option : cmd.get_options()) {
        const std::string name = option->get_name();
        if (option->count() == 0 || skip.contains(name)) continue;
        out.emplace_back(name, option->results());
    }
    return out;
}

std::vector<std::string> as_arguments(const std::vector<GivenOption>& options) {
    std::vector<std::string> args;
    for (const auto& [name, values] : options) {
        // "--name=value", so that a value starting with '-' is not taken for an option.
        for (const std::string& value : values) args.push_back(name + "=" + value);
    }
    return args;
}

}  // namespace slc::cli
