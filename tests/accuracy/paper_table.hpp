// The paper's convergence tables held cell by cell: a study's first rows against the errors the
// paper prints.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <string>

#include "slc/evolve/problems.hpp"
#include "slc/evolve/study.hpp"

namespace slc {

/// E∞ of a paper's table: rows of N/S/K/ε, columns P = 0..4.
template <std::size_t rows>
using PaperErrors = std::array<std::array<double, 5>, rows>;

/// Studies the named problem over the first rows of `paper` and expects every cell ok with an
/// error at most bound(row, P, the paper's error), printing each beside the paper's.
template <std::size_t rows, class Bound>
void expect_errors_at_most(const std::string& problem, const PaperErrors<rows>& paper,
                           Bound bound) {
    const StudyResult table = study(make_problem(problem), static_cast<int>(rows), RunOptions{});
    for (int row = 0; row < static_cast<int>(rows); ++row) {
        for (int refine = 0; refine < 5; ++refine) {
            const StudyCell& cell = table.at(row, refine);
            const double printed = paper[row][refine];
            ASSERT_EQ(cell.status, RunStatus::ok);
            ASSERT_TRUE(cell.e_inf);
            std::printf("row %d, P = %d: E = %.3g (paper %.3g)\n", row + 1, refine, *cell.e_inf,
                        printed);
            EXPECT_LE(*cell.e_inf, bound(row, refine, printed))
                << "row " << row + 1 << ", P = " << refine;
        }
    }
}

}  // namespace slc
