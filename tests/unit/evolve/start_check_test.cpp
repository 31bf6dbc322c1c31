// The start of a user's run (start_check.hpp, one rule for curves and surfaces): a contour that
// keeps the shape is taken at the options' thin depth; one that loses a part, or its area or
// volume, is taken two levels deeper at a time up to the most thin depth (no deeper once that
// changes nothing), and refused, naming the part and the settings, when the deepest loses it too.
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

/// The tolerance of a start of `given`: a cell, and its area within 1e-3 of its length.
StartTolerance keep(const Interface& given) {
    return {.cell = cell, .measure = area(given), .tolerance = 1e-3 * length(given)};
}

TEST(StartCheck, APartTheContoursLoseTakesDeeperThinCells) {
    const Interface given = circles(2);
    // The contour keeps the second circle only from 8 levels of thin cells.
    std::vector<int> asked;
    const auto read = [&](int thin) {
        asked.push_back(thin);
        return thin >= 8 ? given : circles(1);
    };
    const auto [thin, contour] = start_as_given<2>(given, domain, 5, 6, keep(given), read);
    EXPECT_EQ(thin, 8);
    EXPECT_EQ(contour.curve_count(), 2U);
    // The options' depth, then each shallower one, then deeper.
    EXPECT_EQ(asked, (std::vector<int>{6, 5, 4, 3, 2, 1, 0, 8}));
    // Kept at the options' own depth: read once.
    asked.clear();
    EXPECT_EQ(start_as_given<2>(given, domain, 5, 2, keep(given),
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
    // Each depth reads the first circle a little otherwise, the second not at all.
    const auto lost = [](int thin) {
        return Interface({shapes::circle({}, 1.0, 128 + static_cast<std::size_t>(thin))});
    };
    try {
        start_as_given<2>(given, domain, 5, 4, keep(given), lost);
        FAIL() << "no refusal";
    } catch (const NumericalFailure& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("2 components with 0 holes became 1 component with 0 holes, and the "
                         "part near (4, 0) lies 3"),
                  std::string::npos)
            << m;
        EXPECT_NE(m.find("raise -K (--thin-depth is at its most, 8)"), std::string::npos) << m;
    }
    // No thin cells asked for (--thin-depth 0): none are added, and the message says so.
    try {
        start_as_given<2>(given, domain, 5, 0, keep(given), lost);
        FAIL() << "no refusal";
    } catch (const NumericalFailure& e) {
        EXPECT_NE(std::string(e.what()).find("no thin cells"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("raise --thin-depth (now 0) or -K"), std::string::npos)
            << e.what();
    }
}

TEST(StartCheck, DeeperThinCellsThatChangeNothingStopAndNameK) {
    const Interface given = circles(2);
    std::vector<int> asked;
    try {
        start_as_given<2>(given, domain, 5, 2, keep(given), [&](int thin) {
            asked.push_back(thin);
            return circles(1);
        });
        FAIL() << "no refusal";
    } catch (const NumericalFailure& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("(thin cells 4 levels deep split no more than 2 did), as where it tapers "
                         "to an edge or a point of no thickness: give it a thickness of at least"),
                  std::string::npos)
            << m;
        EXPECT_NE(m.find("or raise -K"), std::string::npos) << m;
    }
    EXPECT_EQ(asked, (std::vector<int>{2, 1, 0, 4}));
}

TEST(StartCheck, ThinCellsThatBreakASharpEdgeGiveWayToShallowerOnes) {
    // Thin cells follow a sharp edge or point, thinner than any cell near it, and their corners
    // catch it unevenly: the contour gets a part (a speck at a pyramid's apex, handles beside its
    // edges) at thin depths 1 and up. The deepest shallower depth that keeps the shape is taken.
    const Interface given = circles(1);
    std::vector<int> asked;
    const auto [thin, contour] = start_as_given<2>(given, domain, 5, 2, keep(given), [&](int t) {
        asked.push_back(t);
        return t == 0 ? given : circles(2);
    });
    EXPECT_EQ(thin, 0);
    EXPECT_EQ(contour.curve_count(), 1U);
    EXPECT_EQ(asked, (std::vector<int>{2, 1, 0}));
}

TEST(StartCheck, AnAreaBeyondWhatEpsAllowsIsRefusedNamingK) {
    // The curve kept, but its area 0.8% low (a radius 0.996 for 1): eps = 1e-3 allows
    // 1e-3 times the length, 0.2% of the area.
    const Interface given({shapes::circle({}, 1.0, 256)});
    const Interface smaller({shapes::circle({}, 0.996, 256)});
    try {
        start_as_given<2>(given, domain, 5, 2, keep(given), [&](int) { return smaller; });
        FAIL() << "no refusal";
    } catch (const NumericalFailure& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("the area 3.14128 became 3.1162 (-0.798%; eps allows 0.00628)"),
                  std::string::npos)
            << m;
        EXPECT_NE(m.find("refinement did not bring the contours within eps of it: raise -K"),
                  std::string::npos)
            << m;
    }
    // Within what eps allows: taken.
    const Interface near({shapes::circle({}, 0.9995, 256)});
    EXPECT_EQ(start_as_given<2>(given, domain, 5, 2, keep(given), [&](int) { return near; }).first,
              2);
}

TEST(StartCheck, SurfacesFollowTheSameRule) {
    const Box3 box = Box3::cube({}, 1.0);
    const Surface pair = join({sphere({-0.5, 0, 0}, 0.3, 2), sphere({0.5, 0, 0}, 0.3, 2)});
    const Surface one = sphere({-0.5, 0, 0}, 0.3, 2);
    // One sphere, read a little otherwise at each depth.
    const auto lost = [](int thin) { return sphere({-0.5, 0, 0}, 0.3 + 1e-4 * thin, 2); };
    const StartTolerance tolerance{
        .cell = 0.125, .measure = volume(pair), .tolerance = 1e-3 * area(pair)};
    const auto [thin, contour] = start_as_given<3>(pair, box, 4, 2, tolerance,
                                                   [&](int t) { return t >= 6 ? pair : lost(t); });
    EXPECT_EQ(thin, 6);
    EXPECT_EQ(component_count(contour), 2U);
    EXPECT_THROW(start_as_given<3>(pair, box, 4, 2, tolerance, [&](int) { return one; }),
                 NumericalFailure);
    // Its volume 3% low, kept otherwise: refused.
    Surface shrunk = pair;
    for (Vec3& v : shrunk.vertices) {
        const Vec3 c{v.x < 0.0 ? -0.5 : 0.5, 0.0, 0.0};
        v = c + 0.99 * (v - c);
    }
    try {
        start_as_given<3>(pair, box, 4, 2, tolerance, [&](int) { return shrunk; });
        FAIL() << "no refusal";
    } catch (const NumericalFailure& e) {
        EXPECT_NE(std::string(e.what()).find("the volume "), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("(-2.97%"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace slc::detail
