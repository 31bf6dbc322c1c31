// Velocity laws written in Python. Each is called with whole arrays (all vertices of a stage, or
// a batch of points) on the thread that runs the step, with the GIL held for the call alone.
#include "laws.hpp"

#include <algorithm>
#include <map>

#include "slc/velocity/expression.hpp"
#include "slc/velocity/grid_field.hpp"

namespace slc::python {
namespace {

/// f(t, points, normals, curvature) -> (m, 2) vertex velocities or (m,) normal speeds v (u = v·N),
/// called once per stage with all vertices.
class PythonCurveLaw final : public VelocityLaw {
public:
    PythonCurveLaw(py::object f, std::string name, std::optional<GeometryModule> module)
        : f_(std::move(f)), name_(std::move(name)), module_(module) {}
    std::string name() const override { return name_; }
    GeometryNeeds needs() const override {
        return {.normals = true, .curvature = true, .module = module_};
    }
    std::vector<Vec2> velocities(double t, const Interface& curves,
                                 const VertexGeometry& geometry) const override {
        py::gil_scoped_acquire hold;
        const std::size_t m = curves.size();
        const Array v = numbers_of(
            f_(t, array_of(curves.points()), array_of(std::span<const Vec2>(geometry.normals)),
               array_of(std::span<const double>(geometry.curvature))),
            "velocity '" + name_ + "'");
        std::vector<Vec2> u(m);
        const auto n = static_cast<py::ssize_t>(m);
        if (v.ndim() == 1 && v.shape(0) == n) {
            for (std::size_t i = 0; i < m; ++i) u[i] = v.data()[i] * geometry.normals[i];
        } else if (v.ndim() == 2 && v.shape(0) == n && v.shape(1) == 2) {
            u = vectors_of(v.data(), m);
        } else {
            throw InvalidInput(fmt::format(
                "velocity '{}' must return (m,) normal speeds or (m, 2) velocities for m = {} "
                "vertices, got shape {}",
                name_, m, shape_text(v)));
        }
        return u;
    }

private:
    py::object f_;
    std::string name_;
    std::optional<GeometryModule> module_;
};

/// f(t, points, normals) -> (m,) normal speeds, known off the curve: the step evaluates it where
/// it needs it, with the normal of the distance field (Extension::direct), so corners and offsets
/// move exactly. Called once per batch of points.
class PythonNormalLaw final : public NormalLaw {
public:
    PythonNormalLaw(py::object f, std::string name) : f_(std::move(f)), name_(std::move(name)) {}
    std::string name() const override { return name_; }
    void normal_speeds(double t, std::span<const Vec2> points, std::span<const Vec2> normals,
                       std::span<double> out) const override {
        py::gil_scoped_acquire hold;
        const Array v =
            numbers_of(f_(t, array_of(points), array_of(normals)), "normal speed '" + name_ + "'");
        if (v.ndim() != 1 || static_cast<std::size_t>(v.shape(0)) != points.size()) {
            throw InvalidInput(
                fmt::format("normal speed '{}' must return (m,) speeds for m = {} points, got "
                            "shape {}",
                            name_, points.size(), shape_text(v)));
        }
        std::copy_n(v.data(), out.size(), out.begin());
    }

private:
    py::object f_;
    std::string name_;
};

/// A flow field f(t, points) -> (m, 2) known everywhere: sampled off the curve along the
/// characteristics, one call per batch and Runge–Kutta stage.
class PythonFieldLaw final : public FlowFieldLaw {
public:
    PythonFieldLaw(py::object f, std::string name) : f_(std::move(f)), name_(std::move(name)) {}
    std::string name() const override { return name_; }
    void sample(double t, std::span<const Vec2> points, std::span<Vec2> out) const override {
        py::gil_scoped_acquire hold;
        const Array v = numbers_of(f_(t, array_of(points)), "flow field '" + name_ + "'");
        if (v.ndim() != 2 || v.shape(0) != static_cast<py::ssize_t>(points.size()) ||
            v.shape(1) != 2) {
            throw InvalidInput(
                fmt::format("flow field '{}' must return (m, 2) velocities for m = {} points, got "
                            "shape {}",
                            name_, points.size(), shape_text(v)));
        }
        const std::vector<Vec2> u = vectors_of(v.data(), out.size());
        std::copy(u.begin(), u.end(), out.begin());
    }

private:
    py::object f_;
    std::string name_;
};

}  // namespace

GeometryModule geometry_module(const std::string& name) {
    static const std::map<std::string, GeometryModule> names = {
        {"intrinsic", GeometryModule::intrinsic},
        {"embedded", GeometryModule::embedded},
        {"arclength", GeometryModule::arclength}};
    const auto it = names.find(name);
    if (it == names.end())
        throw InvalidInput("geometry must be one of arclength, embedded, intrinsic, got '" + name +
                           "'");
    return it->second;
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
    if (spec.kind == "field-file") return grid_field_law(spec.velocity.cast<std::string>());
    if (!spec.params.empty())
        throw InvalidInput("params are for the built-in laws, not for a Python velocity");
    if (spec.kind == "flow-field")
        return std::make_unique<PythonFieldLaw>(spec.velocity, spec.name);
    if (spec.kind == "normal") return std::make_unique<PythonNormalLaw>(spec.velocity, spec.name);
    return std::make_unique<PythonCurveLaw>(spec.velocity, spec.name, module);
}

}  // namespace slc::python
