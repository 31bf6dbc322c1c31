// The paper's Table 5 (a propeller turned twice, §4.4) has an error in every cell, P = 0 included,
// where the coarse run's area drifts beyond what the guards let a run keep: the study reports
// those cells too, run again without the guards as the paper's runs are.
#include <gtest/gtest.h>

#include "slc/evolve/problems.hpp"
#include "slc/evolve/study.hpp"

namespace slc {
namespace {

TEST(TableFive, EveryCellOfTheFirstRowHasAnError) {
    const Problem p = make_problem("propeller-rotation");
    const StudyResult table = study(p, 1, RunOptions{});
    int stopped = 0;
    for (int refine = 0; refine < 5; ++refine) {
        const StudyCell& cell = table.at(0, refine);
        SCOPED_TRACE(::testing::Message() << "P = " << refine);
        ASSERT_TRUE(cell.e_inf);
        EXPECT_GT(*cell.e_inf, 0.0);
        if (cell.stopped.empty()) {
            EXPECT_EQ(cell.status, RunStatus::ok);
            continue;
        }
        ++stopped;
        EXPECT_EQ(cell.status, RunStatus::broken);
        EXPECT_NE(cell.stopped.find("t = "), std::string::npos) << cell.stopped;
    }
    // 40/0/3/0: the area leaves ±5% at t ≈ 2.2 of 4π.
    EXPECT_FALSE(table.at(0, 0).stopped.empty());
    EXPECT_GE(stopped, 1);
}

}  // namespace
}  // namespace slc
