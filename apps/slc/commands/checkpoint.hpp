// Checkpoints of `slc run`: DIR/checkpoint.json holds the options the run was given and its state
// after some steps (Γ, t, the step count, counters and clocks; for a surface its vertices and
// triangles), so that `slc run --resume DIR` continues it to the same final interface, bit for
// bit.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "slc/core/box3.hpp"
#include "slc/evolve/run.hpp"
#include "slc/evolve/surface_run.hpp"

namespace slc::cli {

/// An option of the command line as given: its name ("--steps") and its raw values.
using GivenOption = std::pair<std::string, std::vector<std::string>>;

struct Checkpoint {
    std::vector<GivenOption> options;  ///< the run's options, to parse again on resume
    std::string run_id;                ///< the run's identity (run_id), also in its summary.json
    RunResult state;                   ///< after state.steps_done steps (curves)
    int frames_kept = 0;               ///< frames written so far (DIR/frames/frame_0000.json ...)
    /// For a run of a surface: its state after surface->steps_done steps (then `state` is
    /// unused), and the times of the frames kept (DIR/frames/frame_NNNN.vtp and .png).
    std::optional<SurfaceRunResult> surface;
    std::vector<double> frame_times;
};

/// DIR/checkpoint.json.
std::filesystem::path checkpoint_path(const std::filesystem::path& dir);

/// Writes the checkpoint atomically (a killed run leaves the previous one or this one, whole).
/// Doubles are written in the shortest form that reads back to the same bits.
void write_checkpoint(const std::filesystem::path& dir, const Checkpoint& checkpoint);

/// Reads DIR/checkpoint.json; InvalidInput (one line naming the file) when it is missing or not
/// a checkpoint.
Checkpoint read_checkpoint(const std::filesystem::path& dir);

/// Checks a checkpoint read back as an interface file is checked (finite, inside the domain the
/// run had reached, no crossings, oriented as slc writes them), its counters against the run's
/// options, and the results in dir against it: a summary.json of another run, or of a later
/// step, stops the resume. Throws InvalidInput, one line naming the file.
void check_checkpoint(const Checkpoint& checkpoint, const Box& domain, const RunOptions& options,
                      const std::filesystem::path& dir);

/// check_checkpoint for a run of a surface: the surface valid (as a surface file is checked) and
/// inside the domain, its counters against the options, and the results in dir not of another
/// run or a later step. Throws InvalidInput, one line naming the file.
void check_surface_checkpoint(const Checkpoint& checkpoint, const Box3& domain,
                              const SurfaceRunOptions& options, const std::filesystem::path& dir);

/// The identity of a run: 16 hexadecimal digits hashing its options but those that do not change
/// its results (`skip`) and the content of the files the options name (`files`: option names).
std::string run_identity(const std::vector<GivenOption>& options, const std::set<std::string>& skip,
                         const std::set<std::string>& files);

/// The options given to cmd on its command line, except those named in skip.
std::vector<GivenOption> given_options(const CLI::App& cmd, const std::set<std::string>& skip);

/// The options as command-line arguments, in order: "--name=value", ... (long names only).
std::vector<std::string> as_arguments(const std::vector<GivenOption>& options);

}  // namespace slc::cli
