#include "slc/velocity/zero_outside.hpp"

#include <fmt/format.h>

#include <string>
#include <utility>

#include "slc/core/error.hpp"

namespace slc {
namespace {

/// law's field inside its box, zero outside it.
template <int dim>
class ZeroOutside final : public BasicFlowFieldLaw<dim> {
public:
    using Point = PointOf<dim>;

    explicit ZeroOutside(std::unique_ptr<BasicVelocityLaw<dim>> law)
        : law_(std::move(law)), box_(*law_->extent()) {}

    std::string name() const override { return law_->name() + " (zero outside)"; }

    void sample(double t, std::span<const Point> points, std::span<Point> out) const override {
        law_->sample(t, points, out);
        for (std::size_t i = 0; i < points.size(); ++i)
            if (!box_.contains(points[i])) out[i] = Point{};
    }

private:
    std::unique_ptr<BasicVelocityLaw<dim>> law_;
    RegionOf<dim> box_;
};

}  // namespace

template <int dim>
std::unique_ptr<BasicVelocityLaw<dim>> zero_outside_extent(
    std::unique_ptr<BasicVelocityLaw<dim>> law) {
    if (!law->is_field() || !law->extent()) {
        throw InvalidInput(fmt::format(
            "velocity '{}' is not a flow field known in a box, so it has no outside to be zero in",
            law->name()));
    }
    return std::make_unique<ZeroOutside<dim>>(std::move(law));
}

template std::unique_ptr<BasicVelocityLaw<2>> zero_outside_extent(
    std::unique_ptr<BasicVelocityLaw<2>>);
template std::unique_ptr<BasicVelocityLaw<3>> zero_outside_extent(
    std::unique_ptr<BasicVelocityLaw<3>>);

}  // namespace slc
