// The paper's Table 7 (a circle of radius √5 shrinking under curvature to t = 2, §4.6.1) is fully
// specified, so each of our errors can be held to the paper's: here the first three rows of the
// study (N ≤ 80, every P), with the errors the paper prints.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>

#include "slc/evolve/problems.hpp"
#include "slc/evolve/study.hpp"

namespace slc {
namespace {

/// E∞ of the paper's Table 7, rows 20/1/3/1e−3, 40/1/4/1e−4, 80/1/5/1e−5, columns P = 0..4.
constexpr std::array<std::array<double, 5>, 3> paper_errors{{
    {0.106, 0.13, 0.072, 0.057, 0.057},
    {0.0664, 0.0454, 0.0241, 0.016, 0.0142},
    {0.0305, 0.0186, 0.00909, 0.00501, 0.00376},
}};

TEST(TableSeven, EveryErrorOfTheFirstThreeRowsIsAtMostThePapers) {
    const Problem p = make_problem("circle-curvature");
    const StudyResult table = study(p, 3, RunOptions{});
    for (int row = 0; row < 3; ++row) {
        for (int refine = 0; refine < 5; ++refine) {
            const StudyCell& cell = table.at(row, refine);
            const double paper = paper_errors[row][refine];
            ASSERT_EQ(cell.status, RunStatus::ok);
            ASSERT_TRUE(cell.e_inf);
            std::printf("row %d, P = %d: E = %.3g (paper %.3g)\n", row + 1, refine, *cell.e_inf,
                        paper);
            EXPECT_LE(*cell.e_inf, paper) << "row " << row + 1 << ", P = " << refine;
        }
    }
}

}  // namespace
}  // namespace slc
