// Velocity laws written in Python. Each is called with whole arrays (all vertices of a stage, or
// a batch of points) on the thread that runs the step, with the GIL held for the call alone.
#include "laws.hpp"

#include <algorithm>
#include <map>

#include "slc/evolve/surface_problems.hpp"
#include "slc/io/vdb.hpp"
#include "slc/velocity/expression.hpp"
#include "slc/velocity/grid_field.hpp"
#include "slc/velocity/zero_outside.hpp"

namespace slc::python {
namespace {

/// The columns of a dimension's points: 2 for curves, 3 for surfaces.
template <int dim>
constexpr py::ssize_t columns = dim;

/// What every law written in Python holds: the callable f and the name the law goes by.
template <class Law>
class PythonLaw : public Law {
public:
    PythonLaw(py::object f, std::string name) : f_(std::move(f)), name_(std::move(name)) {}
    std::string name() const override { return name_; }

protected:
    py::object f_;
    std::string name_;
};

/// f(t, points, normals, curvature) -> (m, dim) vertex velocities or (m,) normal speeds v
/// (u = v·N), called once per stage with all vertices; f(t, points, normals) when it takes no
/// curvature (curvature false). A surface's curvature is then not computed; a curve's still is,
/// for little, so that the run takes a curvature law's defaults (P = 2, arcs): refined to
/// convergence instead, the kinks of the nearest-point extension fed new segments, and a
/// rotation written so went from 128 to 20,000 segments and off its shape by 1.3 in a turn.
template <int dim>
class PythonCurveLaw final : public PythonLaw<BasicVelocityLaw<dim>> {
public:
    using Law = BasicVelocityLaw<dim>;
    using Point = PointOf<dim>;
    PythonCurveLaw(py::object f, std::string name, std::optional<GeometryModule> module,
                   bool curvature)
        : PythonLaw<Law>(std::move(f), std::move(name)), module_(module), curvature_(curvature) {}
    GeometryNeeds needs() const override {
        return {.normals = true, .curvature = curvature_ || dim == 2, .module = module_};
    }
    /// u, and where f reads the curvature, its normal part's slope in C checked (two calls more,
    /// at C ± h), as a speed expression's is: a law that moves the most convex parts out the
    /// fastest is ill-posed.
    std::vector<Point> velocities(double t, const ShapeOf<dim>& shape,
                                  const GeometryOf<dim>& geometry) const override {
        py::gil_scoped_acquire hold;
        const std::span<const Point> points = vertex_points(shape);
        const py::object x = array_of(points);
        const py::object normals = array_of(std::span<const Point>(geometry.normals));
        if (!curvature_) return velocities_of(this->f_(t, x, normals), geometry.normals);
        const std::span<const double> c(geometry.curvature);
        std::vector<Point> u =
            velocities_of(this->f_(t, x, normals, array_of(c)), geometry.normals);
        std::vector<double> h(c.size()), shifted(c.size());
        for (std::size_t i = 0; i < c.size(); ++i) h[i] = 0x1p-20 * std::max(1.0, std::abs(c[i]));
        const auto at = [&](double sign) {
            for (std::size_t i = 0; i < c.size(); ++i) shifted[i] = c[i] + sign * h[i];
            return velocities_of(
                this->f_(t, x, normals, array_of(std::span<const double>(shifted))),
                geometry.normals);
        };
        const std::vector<Point> above = at(1.0), below = at(-1.0);
        std::vector<double> slope(c.size());
        for (std::size_t i = 0; i < c.size(); ++i)
            slope[i] = dot(above[i] - below[i], geometry.normals[i]) / (2.0 * h[i]);
        require_forward_in_curvature("velocity '" + this->name_ + "'", points, slope);
        return u;
    }

private:
    /// f's answer as vertex velocities: (m,) normal speeds times the normals, or (m, dim).
    std::vector<Point> velocities_of(const py::object& answer,
                                     std::span<const Point> normals) const {
        const Array v = numbers_of(answer, "velocity '" + this->name_ + "'");
        const std::size_t m = normals.size();
        const auto n = static_cast<py::ssize_t>(m);
        std::vector<Point> u(m);
        if (v.ndim() == 1 && v.shape(0) == n) {
            for (std::size_t i = 0; i < m; ++i) u[i] = v.data()[i] * normals[i];
        } else if (v.ndim() == 2 && v.shape(0) == n && v.shape(1) == columns<dim>) {
            u = points_from<Point>(v.data(), m);
        } else {
            throw InvalidInput(fmt::format(
                "velocity '{}' must return (m,) normal speeds or (m, {}) velocities for m = {} "
                "vertices, got shape {}",
                this->name_, dim, m, shape_text(v)));
        }
        return u;
    }

private:
    std::optional<GeometryModule> module_;
    bool curvature_;
};

/// f(t, points, normals) -> (m,) normal speeds, known off the interface: the step evaluates it
/// where it needs it, with the normal of the distance field (Extension::direct), so corners and
/// offsets move exactly. Called once per batch of points.
template <int dim>
class PythonNormalLaw final : public PythonLaw<BasicNormalLaw<dim>> {
public:
    using PythonLaw<BasicNormalLaw<dim>>::PythonLaw;
    using Point = PointOf<dim>;
    void normal_speeds(double t, std::span<const Point> points, std::span<const Point> normals,
                       std::span<double> out) const override {
        py::gil_scoped_acquire hold;
        const Array v = numbers_of(this->f_(t, array_of(points), array_of(normals)),
                                   "normal speed '" + this->name_ + "'");
        if (v.ndim() != 1 || static_cast<std::size_t>(v.shape(0)) != points.size()) {
            throw InvalidInput(
                fmt::format("normal speed '{}' must return (m,) speeds for m = {} points, got "
                            "shape {}",
                            this->name_, points.size(), shape_text(v)));
        }
        std::copy_n(v.data(), out.size(), out.begin());
    }
};

/// A flow field f(t, points) -> (m, dim) known everywhere: sampled off the interface along the
/// characteristics, one call per batch and Runge–Kutta stage.
template <int dim>
class PythonFieldLaw final : public PythonLaw<BasicFlowFieldLaw<dim>> {
public:
    using PythonLaw<BasicFlowFieldLaw<dim>>::PythonLaw;
    using Point = PointOf<dim>;
    void sample(double t, std::span<const Point> points, std::span<Point> out) const override {
        py::gil_scoped_acquire hold;
        const Array v =
            numbers_of(this->f_(t, array_of(points)), "flow field '" + this->name_ + "'");
        if (v.ndim() != 2 || v.shape(0) != static_cast<py::ssize_t>(points.size()) ||
            v.shape(1) != columns<dim>) {
            throw InvalidInput(
                fmt::format("flow field '{}' must return (m, {}) velocities for m = {} points, "
                            "got shape {}",
                            this->name_, dim, points.size(), shape_text(v)));
        }
        const std::vector<Point> u = points_from<Point>(v.data(), out.size());
        std::copy(u.begin(), u.end(), out.begin());
    }
};

/// The law of a Python callable in dimension dim, by spec.kind: flow-field, normal, or vertex
/// velocities (vertex, with curvature, or vertex-no-curvature); module for curves' geometry.
template <int dim>
std::unique_ptr<BasicVelocityLaw<dim>> python_law(const LawSpec& spec,
                                                  std::optional<GeometryModule> module) {
    if (!spec.params.empty())
        throw InvalidInput("params are for the built-in laws, not for a Python velocity");
    if (spec.kind == "flow-field")
        return std::make_unique<PythonFieldLaw<dim>>(spec.velocity, spec.name);
    if (spec.kind == "normal")
        return std::make_unique<PythonNormalLaw<dim>>(spec.velocity, spec.name);
    return std::make_unique<PythonCurveLaw<dim>>(spec.velocity, spec.name, module,
                                                 spec.kind != "vertex-no-curvature");
}

}  // namespace

GeometryModule geometry_module(const std::string& name) {
    return value_named<GeometryModule>(geometry_module_names, name, "geometry");
}

std::unique_ptr<VelocityLaw> make_law(const LawSpec& spec) {
    const std::optional<GeometryModule> module =
        spec.geometry ? std::optional(geometry_module(*spec.geometry)) : std::nullopt;
    if (spec.kind == "builtin")
        return make_velocity(spec.velocity.cast<std::string>(), spec.params, module);
    if (spec.kind == "speed")
        return speed_expression_law(spec.velocity.cast<std::string>(), spec.params, module);
    if (spec.kind == "field")
        return field_expression_law(spec.velocity.cast<std::string>(), spec.params);
    if (spec.kind == "field-file") {
        const std::string path = spec.velocity.cast<std::string>();
        if (is_vdb_file(path)) {
            throw InvalidInput(fmt::format(
                "FieldFile('{}'): an OpenVDB field (.vdb) moves surfaces, not curves", path));
        }
        auto law = grid_field_law(path);
        return spec.zero_outside ? zero_outside_extent(std::move(law)) : std::move(law);
    }
    return python_law<2>(spec, module);
}

std::unique_ptr<SurfaceVelocityLaw> make_surface_law(const LawSpec& spec) {
    if (spec.geometry)
        throw InvalidInput("geometry is for curves: surfaces have one geometry module");
    if (spec.kind == "builtin")
        return make_surface_velocity(spec.velocity.cast<std::string>(), spec.params);
    if (spec.kind == "speed")
        return surface_speed_expression_law(spec.velocity.cast<std::string>(), spec.params);
    if (spec.kind == "field")
        return surface_field_expression_law(spec.velocity.cast<std::string>(), spec.params);
    if (spec.kind == "field-file") {
        const std::string path = spec.velocity.cast<std::string>();
        if (!is_vdb_file(path)) {
            throw InvalidInput(fmt::format(
                "FieldFile for a surface takes an OpenVDB vector grid (.vdb), got '{}'", path));
        }
        auto law = vdb_field_law(path);
        return spec.zero_outside ? zero_outside_extent(std::move(law)) : std::move(law);
    }
    return python_law<3>(spec, std::nullopt);
}

}  // namespace slc::python
