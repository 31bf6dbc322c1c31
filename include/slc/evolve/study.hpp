/// @file
/// Convergence studies (paper §4.2, Tables 5–7, Figure 10): a 5×5 table of runs whose rows refine
/// N, K and ε together (N ← 2N, K ← K + 1, ε ← ε/10) and whose columns add passes of adaptive
/// refinement (P = 0..4), with the observed orders of convergence.
#pragma once

#include <cmath>
#include <functional>
#include <optional>
#include <vector>

#include "slc/evolve/problems.hpp"
#include "slc/evolve/run.hpp"

namespace slc {

/// One run of a study.
struct StudyCell {
    int row = 0;                       ///< 0..rows − 1: N, K and ε refined `row` times
    int refine = 0;                    ///< P, the column
    RunOptions options;                ///< the run's settings (N/S/K/P/ε resolved)
    RunStatus status = RunStatus::ok;  ///< how the run ended
    /// Why the guards stopped this cell's run (its message, naming the time), when they did: the
    /// cell is then run again without them, as the paper's runs are, and status and e_inf are
    /// that run's (status broken).
    std::string stopped;
    std::optional<double> e_inf;      ///< the error of Equation (11) at the end
    double cpu_s_per_step = 0.0;      ///< process CPU seconds of the time loop / N
    double g_evals_per_vertex = 0.0;  ///< G evaluations / vertices produced, whole run
    std::size_t segments = 0;         ///< segments of the final curves
};

/// log2(coarse / fine), the observed order between two errors; nullopt where one is missing or
/// not positive.
inline std::optional<double> observed_order(const std::optional<double>& coarse,
                                            const std::optional<double>& fine) {
    if (!coarse || !fine || !(*coarse > 0.0) || !(*fine > 0.0)) return std::nullopt;
    return std::log2(*coarse / *fine);
}

/// The table of a study: rows × columns runs (cells with e_inf) with their errors and costs.
template <class Cell>
struct BasicStudyResult {
    int rows = 0;             ///< runs refining N, K, ε together
    int columns = 0;          ///< P = 0..columns − 1
    std::vector<Cell> cells;  ///< row-major

    /// The cell in row `row` and column `column` (P = column).
    const Cell& at(int row, int column) const {
        return cells[static_cast<std::size_t>(row * columns + column)];
    }
    /// log2(E(row, P) / E(row, P + 1)): about 1 while refinement controls the error (first order
    /// in the segment length, which halves per pass). nullopt where an error is missing or zero.
    std::optional<double> row_order(int row, int column) const {
        if (column + 1 >= columns) return std::nullopt;
        return observed_order(at(row, column).e_inf, at(row, column + 1).e_inf);
    }
    /// log2(E(row, P) / E(row + 1, P)): about 2 in the P = 4 column (second order in time, k
    /// halving per row), 1 where the spatial error still dominates.
    std::optional<double> column_order(int row, int column) const {
        if (row + 1 >= rows) return std::nullopt;
        return observed_order(at(row, column).e_inf, at(row + 1, column).e_inf);
    }
};

/// The table of a study of curves.
using StudyResult = BasicStudyResult<StudyCell>;

/// The options of one cell of the problem's study plan: `base` (η, ρ, E, extension, ... kept)
/// with N, K, ε, S and M of row `row` (0-based) and P = refine. Throws InvalidInput for a row
/// outside 0..4 or a refine outside 0..4.
RunOptions study_cell_options(const Problem& problem, int row, int refine, const RunOptions& base);

/// Called after each run with the finished cell.
using StudyObserver = std::function<void(const StudyCell&)>;

/// Runs `rows` rows (1..5) of the problem's study plan with method options `base` (η, ρ, E,
/// extension, ... kept; N, K, ε, S, P set by the plan). Throws InvalidInput for rows out of range.
StudyResult study(const Problem& problem, int rows, const RunOptions& base,
                  const StudyObserver& observer = {});

}  // namespace slc
