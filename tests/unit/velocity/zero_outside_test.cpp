// Tests of a field known in a box taken as zero outside it, in both dimensions: the field inside,
// zero outside, known everywhere, and refused for laws without a box.
#include "slc/velocity/zero_outside.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/velocity/factory.hpp"
#include "slc/velocity/grid_field.hpp"

namespace slc {
namespace {

/// The rotation (−y, x) on the lattice of 5 × 5 points over [−1, 1]².
std::unique_ptr<VelocityLaw> rotation_lattice() {
    GridVelocity g{{-1, -1}, {0.5, 0.5}, 5, 5, {}};
    for (std::size_t j = 0; j < 5; ++j)
        for (std::size_t i = 0; i < 5; ++i)
            g.values.push_back(
                {-(-1 + 0.5 * static_cast<double>(j)), -1 + 0.5 * static_cast<double>(i)});
    return std::make_unique<GridField>(std::move(g), "lattice");
}

/// The rotation (−y, x, 0) known in [0, 1]³ only, as a grid's field is.
class BoxedRotation final : public SurfaceFlowFieldLaw {
public:
    std::string name() const override { return "boxed"; }
    void sample(double, std::span<const Vec3> points, std::span<Vec3> out) const override {
        for (std::size_t i = 0; i < points.size(); ++i) out[i] = {-points[i].y, points[i].x, 0.0};
    }
    std::optional<Box3> extent() const override { return Box3{{0, 0, 0}, {1, 1, 1}}; }
};

TEST(ZeroOutside, CurvesTheLatticesFieldInsideAndZeroOutside) {
    const auto law = zero_outside_extent(rotation_lattice());
    EXPECT_EQ(law->name(), "lattice (zero outside)");
    EXPECT_TRUE(law->is_field());
    EXPECT_FALSE(law->extent().has_value());  // known everywhere: a run no longer refuses
    const std::vector<Vec2> x = {{0.3, -0.7}, {1.0, 1.0}, {1.0 + 1e-12, 0.0}, {-3.0, 0.5}};
    std::vector<Vec2> u(x.size());
    law->sample(0.0, x, u);
    EXPECT_NEAR(u[0].x, 0.7, 1e-12);  // inside: the lattice's own (exact for a linear field)
    EXPECT_NEAR(u[0].y, 0.3, 1e-12);
    EXPECT_NEAR(u[1].x, -1.0, 1e-12);  // on the box's edge, still inside
    EXPECT_EQ(u[2], Vec2{});           // beyond it, zero
    EXPECT_EQ(u[3], Vec2{});
}

TEST(ZeroOutside, SurfacesTheFieldInsideAndZeroOutside) {
    const auto law = zero_outside_extent<3>(std::make_unique<BoxedRotation>());
    EXPECT_EQ(law->name(), "boxed (zero outside)");
    EXPECT_FALSE(law->extent().has_value());
    const std::vector<Vec3> x = {{0.5, 0.25, 0.5}, {0.5, 0.5, 1.5}, {-0.1, 0.5, 0.5}};
    std::vector<Vec3> u(x.size());
    law->sample(0.0, x, u);
    EXPECT_EQ(u[0], (Vec3{-0.25, 0.5, 0.0}));
    EXPECT_EQ(u[1], Vec3{});
    EXPECT_EQ(u[2], Vec3{});
}

TEST(ZeroOutside, RefusesALawKnownEverywhere) {
    try {
        zero_outside_extent(make_velocity("rotation", {}));
        FAIL() << "no InvalidInput";
    } catch (const InvalidInput& e) {
        EXPECT_STREQ(e.what(),
                     "velocity 'rotation' is not a flow field known in a box, so it has no "
                     "outside to be zero in");
    }
    EXPECT_THROW(zero_outside_extent(make_surface_velocity("unit-normal", {})), InvalidInput);
}

}  // namespace
}  // namespace slc
