// slc run on a surface (DESIGN §8): a named surface problem, or the user's surface file under a
// built-in law of surfaces or an expression.
#pragma once

#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "commands/checkpoint.hpp"
#include "commands/common.hpp"
#include "commands/output_folder.hpp"
#include "slc/evolve/surface_problems.hpp"

namespace slc::cli {

/// What `slc run` was given, for a surface.
struct SurfaceRunRequest {
    std::string problem;               ///< a surface problem, or empty
    std::string initial;               ///< a surface file, or empty
    std::string velocity;              ///< the law of --initial by name, or empty
    std::optional<std::string> speed;  ///< or a normal speed expression (--speed)
    std::optional<std::string> field;  ///< or a flow field expression "U, V, W" (--field)
    /// or a flow field on an OpenVDB vector grid (--field-file F.vdb)
    std::optional<std::string> field_file;
    bool field_zero_outside = false;  ///< --field-outside zero
    std::vector<std::string> params;  ///< key=value
    std::optional<double> t_end;
    DomainOptions domain;
    /// N, K, P, ε, η, L, the thin depth, the volume correction (area_correction), the volume
    /// drift and the guards as given; apply_overrides refuses the settings of curves by name.
    RunOverrides settings;
    int frames = 0;
    /// --estimate: the run again at half resolution, and the distance between the two final
    /// surfaces in summary.json's "error_estimate".
    bool estimate = false;
    std::optional<std::string> view;  ///< "AZ,EL" in degrees
    /// --vdb: the final surface also as DIR/final.vdb, an OpenVDB level set.
    bool vdb = false;
    /// --vdb-voxel: its voxel size; unset: default_vdb_voxel.
    std::optional<double> vdb_voxel;
    bool quiet = false;
    /// Write DIR/checkpoint.json every n steps (and when a signal stops the run); 0: never.
    int checkpoint_every = 0;
    std::vector<GivenOption> given;    ///< the options to keep in checkpoints
    std::string run_id;                ///< the run's identity (run_identity)
    const Checkpoint* from = nullptr;  ///< the checkpoint of --resume, or none
    /// The signal that asked the run to stop (SIGINT, SIGTERM; 0 while none did), read after
    /// every step: the run then ends with status interrupted, writes its results whole and
    /// throws Interrupted.
    const std::atomic<int>* stop_signal = nullptr;
};

/// A surface run's problem (its law, domain and surface as given: a user's surface not yet
/// contoured as the steps read it) and options, from the request.
struct SurfaceRunSetup {
    SurfaceProblem problem;
    SurfaceRunOptions options;
};

/// The problem and options of request: command line over the problem's settings or the
/// defaults of a user's surface. Throws InvalidInput for a missing or second law, a missing
/// --t-end, bad parameters or files, and ε below η.
SurfaceRunSetup resolve_surface_run(const SurfaceRunRequest& request);

/// True when `slc run` was given a surface problem or a surface file.
bool is_surface_run(const std::string& problem, const std::string& initial);

/// The voxel size of final.vdb when --vdb-voxel is not given: half the edge of the contour's
/// cells at depth K in domain, and at most 1/128 of the domain's width, so the level set resolves
/// what the run's contour does.
double default_vdb_voxel(const Box3& domain, int depth);

/// Runs (from request.from when given), writes final.obj, final.vtp, final.png, final.vdb (with
/// request.vdb, unless nothing is left), history.csv/.png, frames (frames.pvd, frames/*.vtp and
/// *.png), checkpoints and summary.json (last) into folder and commits it. Throws NumericalFailure
/// after writing everything when the run ends with status error or unstable, Interrupted when a
/// signal stopped it.
void run_surface(const SurfaceRunRequest& request, OutputFolder& folder);

}  // namespace slc::cli
