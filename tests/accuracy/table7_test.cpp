// The paper's Table 7 (a circle of radius √5 shrinking under curvature to t = 2, §4.6.1) is fully
// specified, so each of our errors can be held to the paper's: here the first three rows of the
// study (N ≤ 80, every P), with the errors the paper prints.
#include <gtest/gtest.h>

#include "paper_table.hpp"

namespace slc {
namespace {

/// E∞ of the paper's Table 7, rows 20/1/3/1e−3, 40/1/4/1e−4, 80/1/5/1e−5, columns P = 0..4.
constexpr PaperErrors<3> paper_errors{{
    {0.106, 0.13, 0.072, 0.057, 0.057},
    {0.0664, 0.0454, 0.0241, 0.016, 0.0142},
    {0.0305, 0.0186, 0.00909, 0.00501, 0.00376},
}};

TEST(TableSeven, EveryErrorOfTheFirstThreeRowsIsAtMostThePapers) {
    expect_errors_at_most("circle-curvature", paper_errors,
                          [](int, int, double paper) { return paper; });
}

}  // namespace
}  // namespace slc
