// The start of a user's run (start_check.hpp, one rule for curves and surfaces): a contour that
// keeps the shape is taken at the options' thin depth; one that loses a part is taken two levels
// deeper at a time up to the most thin depth, and refused, naming the part and the settings, when
// the deepest loses it too.
#include "start_check.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "slc/geometry/shapes.hpp"
#include "slc/geometry/surface_shapes.hpp"

namespace slc::detail {
namespace {

Interface circles(std::size_t count) {
    std::vector<std::vector<Vec2>> c;
    for (std::size_t i = 0; i < count; ++i)
        c.push_back(shapes::circle({3.0 * static_cast<double>(i), 0.0}, 1.0, 128));
    return Interface(c);
}

const Box domain{{-2.0, -2.0}, {6.0, 6.0}};
constexpr double cell = 0.25;

TEST(StartCheck, APartTheContoursLoseTakesDeeperThinCells) {
    const Interface given = circles(2);
    // The contour keeps the second circle only from 8 levels of thin cells.
    std::vector<int> asked;
    const auto read = [&](int thin) {
        asked.push_back(thin);
        return thin >= 8 ? given : circles(1);
    };
    const auto [thin, contour] = start_as_given<2>(given, domain, 5, 6, cell, read);
    EXPECT_EQ(thin, 8);
    EXPECT_EQ(contour.curve_count(), 2U);
    EXPECT_EQ(asked, (std::vector<int>{6, 8}));
    // Kept at the options' own depth: read once.
    asked.clear();
    EXPECT_EQ(start_as_given<2>(given, domain, 5, 2, cell,
                                [&](int t) {
                                    asked.push_back(t);
                                    return given;
                                })
                  .first,
              2);
    EXPECT_EQ(asked, (std::vector<int>{2}));
}

TEST(StartCheck, APartTheDeepestLosesIsRefusedNamingIt) {
    const Interface given = circles(2);
    try {
        start_as_given<2>(given, domain, 5, 4, cell, [&](int) { return circles(1); });
        FAIL() << "no refusal";
    } catch (const NumericalFailure& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("2 components with 0 holes became 1 component with 0 holes, and the "
                         "part near (4, 0) lies 3 from them"),
                  std::string::npos)
            << m;
        EXPECT_NE(m.find("raise -K (--thin-depth is at its most, 8)"), std::string::npos) << m;
    }
    // No thin cells asked for (--thin-depth 0): none are added, and the message says so.
    try {
        start_as_given<2>(given, domain, 5, 0, cell, [&](int) { return circles(1); });
        FAIL() << "no refusal";
    } catch (const NumericalFailure& e) {
        EXPECT_NE(std::string(e.what()).find("no thin cells"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("raise --thin-depth (now 0) or -K"), std::string::npos)
            << e.what();
    }
}

TEST(StartCheck, SurfacesFollowTheSameRule) {
    const Box3 box = Box3::cube({}, 1.0);
    const Surface pair = join({sphere({-0.5, 0, 0}, 0.3, 2), sphere({0.5, 0, 0}, 0.3, 2)});
    const Surface one = sphere({-0.5, 0, 0}, 0.3, 2);
    const auto [thin, contour] =
        start_as_given<3>(pair, box, 4, 2, 0.125, [&](int t) { return t >= 6 ? pair : one; });
    EXPECT_EQ(thin, 6);
    EXPECT_EQ(component_count(contour), 2U);
    EXPECT_THROW(start_as_given<3>(pair, box, 4, 2, 0.125, [&](int) { return one; }),
                 NumericalFailure);
}

}  // namespace
}  // namespace slc::detail
